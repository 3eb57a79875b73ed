// The process's memory locked in RAM (mlockall(MCL_CURRENT | MCL_FUTURE)), held while the haptic
// loop runs, so that no page the loop touches is paged out or mapped late: a page fault in the
// loop's thread waits on the kernel's memory work, behind whatever other thread holds it (the
// 16.4 ms late tick of issue 34, on a machine whose own floor was 2.8 ms). Locking is process-wide:
// one real-time loop per process (the session's), whose release unlocks everything.
//
// Asked only where it cannot hurt the rest of the process: with a finite RLIMIT_MEMLOCK and no
// CAP_IPC_LOCK, MCL_FUTURE would make every allocation beyond the limit fail later, so it is not
// asked and the refusal says why; under a sanitizer, MCL_CURRENT would fault in its terabytes of
// shadow, so neither.
#pragma once

#include <string>

namespace echosim::haptics {

class MemoryLock {
public:
    MemoryLock() = default;  // holds nothing
    // Locks, where permitted. Never throws: a refusal is held as a message.
    static MemoryLock lock_all();
    ~MemoryLock();
    MemoryLock(MemoryLock&& other) noexcept;
    MemoryLock& operator=(MemoryLock&& other) noexcept;
    MemoryLock(const MemoryLock&) = delete;
    MemoryLock& operator=(const MemoryLock&) = delete;

    bool held() const { return held_; }
    // why the memory is not locked ("" when it is, or when nothing was asked)
    const std::string& refusal() const { return refusal_; }
    void release();  // munlockall

private:
    bool held_ = false;
    std::string refusal_;
};

}  // namespace echosim::haptics

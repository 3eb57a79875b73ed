#include "haptics/memory_lock.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <utility>

#include <sys/mman.h>
#include <sys/resource.h>

namespace echosim::haptics {
namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// CAP_IPC_LOCK (14) among this process's effective capabilities (/proc/self/status, CapEff in hex)
bool can_lock_beyond_the_limit()
{
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("CapEff:", 0) == 0) return ((std::strtoull(line.c_str() + 7, nullptr, 16) >> 14) & 1) != 0;
    return false;
}

}  // namespace

MemoryLock MemoryLock::lock_all()
{
    MemoryLock m;
    if (kSanitized) {
        m.refusal_ = "memory not locked: built with a sanitizer (its shadow memory would be faulted in)";
        return m;
    }
    rlimit limit{};
    if (getrlimit(RLIMIT_MEMLOCK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && !can_lock_beyond_the_limit()) {
        m.refusal_ = "memory not locked: RLIMIT_MEMLOCK is " + std::to_string(limit.rlim_cur / 1024) +
                     " KiB and no CAP_IPC_LOCK (grant 'memlock unlimited' in /etc/security/limits.d)";
        return m;
    }
    if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
        m.refusal_ = std::string("memory not locked: mlockall: ") + std::strerror(errno);
        return m;
    }
    m.held_ = true;
    return m;
}

MemoryLock::~MemoryLock() { release(); }

MemoryLock::MemoryLock(MemoryLock&& other) noexcept : held_(std::exchange(other.held_, false)), refusal_(std::move(other.refusal_)) {}

MemoryLock& MemoryLock::operator=(MemoryLock&& other) noexcept
{
    if (this != &other) {
        release();
        held_ = std::exchange(other.held_, false);
        refusal_ = std::move(other.refusal_);
    }
    return *this;
}

void MemoryLock::release()
{
    if (held_) munlockall();
    held_ = false;
}

}  // namespace echosim::haptics

// A lock-free triple buffer: one writer publishes whole values, one reader takes the latest one.
// Neither waits for the other: the writer fills its private slot and swaps it with the shared
// "latest" slot; the reader swaps that with its own when something new was published. It is the
// hand-off between the threads (the physics and its readers, the haptic loop and its device and
// session): the values are allocated up front (the constructor's prototype) so the hot
// paths never allocate.
#pragma once

#include <atomic>
#include <cstdint>

namespace echosim {

template <class T>
class TripleBuffer {
public:
    explicit TripleBuffer(const T& prototype = T{}) : slots_{prototype, prototype, prototype} {}

    // writer side: fill write_slot(), then publish()
    T& write_slot() { return slots_[write_]; }
    void publish()
    {
        const std::uint8_t old = latest_.exchange(std::uint8_t(write_ | kFresh), std::memory_order_acq_rel);
        write_ = old & kIndex;
    }

    // reader side: the newest published value (or the previous one, if nothing new came)
    const T& read()
    {
        if (latest_.load(std::memory_order_acquire) & kFresh) {
            const std::uint8_t old = latest_.exchange(read_, std::memory_order_acq_rel);
            read_ = old & kIndex;
        }
        return slots_[read_];
    }

private:
    static constexpr std::uint8_t kIndex = 0x3, kFresh = 0x4;
    T slots_[3];
    std::uint8_t write_ = 0, read_ = 1;
    std::atomic<std::uint8_t> latest_{2};
};

}  // namespace echosim

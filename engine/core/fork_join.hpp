// A fixed team of threads for the data-parallel loops inside one stage (the physics step's row
// sweeps and vector passes). run(task) calls task(part) for every part in [0, parts()) at once, the
// calling thread taking part 0, and returns when all parts are done; the parts write disjoint data
// and their results are combined by the caller afterwards, in part order (so a computation repeats
// itself bit for bit with a team of the same size). A team of one runs the task inline and starts
// no thread.
//
// Hand-off: the caller publishes the task, then bumps `generation_` (release); a worker that sees
// the new generation (acquire) runs its part and counts down `pending_` (release), which the caller
// waits on (acquire). Workers spin for a short while between tasks, since a step issues dozens of
// them back to back, then sleep on the generation; so a team should not outnumber the free cores.
// One caller at a time; tasks must not throw.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <utility>
#include <vector>

namespace echosim {

class ForkJoin {
public:
    static constexpr int kMaxParts = 64;

    explicit ForkJoin(int parts = 1);
    ~ForkJoin();
    ForkJoin(const ForkJoin&) = delete;
    ForkJoin& operator=(const ForkJoin&) = delete;

    int parts() const { return parts_; }

    template <class Task>
    void run(Task&& task)
    {
        run_erased([](void* t, int part) { (*static_cast<std::remove_reference_t<Task>*>(t))(part); }, &task);
    }

private:
    void run_erased(void (*fn)(void*, int), void* task);
    void work(int part);
    void stop_workers();

    int parts_ = 1;
    std::vector<std::thread> workers_;
    // 32 bits: the size the futex behind atomic wait/notify works on directly (wrapping is harmless:
    // workers only compare it for equality)
    std::atomic<std::uint32_t> generation_{0};
    std::atomic<int> pending_{0};
    std::atomic<bool> stop_{false};
    void (*fn_)(void*, int) = nullptr;
    void* task_ = nullptr;
};

// The share [begin, end) of `total` items that part `part` of `parts` takes: contiguous, sizes
// differing by at most one.
inline std::pair<std::size_t, std::size_t> part_range(std::size_t total, int part, int parts)
{
    const std::size_t p = std::size_t(part), k = std::size_t(parts);
    return {total * p / k, total * (p + 1) / k};
}

}  // namespace echosim

#include "core/fork_join.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define ECHOSIM_PAUSE() _mm_pause()
#else
#define ECHOSIM_PAUSE() std::this_thread::yield()
#endif

namespace echosim {
namespace {

// How long a worker spins for the next task before it sleeps: longer than the gaps between the
// tasks of one step, far shorter than a frame.
constexpr auto kSpin = std::chrono::microseconds(200);

}  // namespace

ForkJoin::ForkJoin(int parts) : parts_(parts)
{
    if (parts < 1 || parts > kMaxParts)
        throw std::invalid_argument("threads: " + std::to_string(parts) + " (1 to " + std::to_string(kMaxParts) + ")");
    try {
        for (int part = 1; part < parts; ++part) workers_.emplace_back([this, part] { work(part); });
    } catch (...) {
        stop_workers();  // the threads already started must be joined before they are destroyed
        throw;
    }
}

ForkJoin::~ForkJoin() { stop_workers(); }

void ForkJoin::stop_workers()
{
    stop_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
}

void ForkJoin::run_erased(void (*fn)(void*, int), void* task)
{
    if (parts_ == 1) {
        fn(task, 0);
        return;
    }
    fn_ = fn;
    task_ = task;
    pending_.store(parts_ - 1, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    fn(task, 0);
    // the other parts take about as long as ours; should a worker have lost its core, let it run
    for (int spins = 0; pending_.load(std::memory_order_acquire) != 0; ++spins)
        if (spins < 4096) ECHOSIM_PAUSE();
        else std::this_thread::yield();
}

void ForkJoin::work(int part)
{
    std::uint32_t seen = 0;
    for (;;) {
        std::uint32_t now = generation_.load(std::memory_order_acquire);
        const auto until = std::chrono::steady_clock::now() + kSpin;
        for (int spins = 0; now == seen; ++spins) {
            if (spins % 64 == 63 && std::chrono::steady_clock::now() > until) {
                generation_.wait(seen, std::memory_order_acquire);
                spins = 0;
            } else {
                ECHOSIM_PAUSE();
            }
            now = generation_.load(std::memory_order_acquire);
        }
        seen = now;
        if (stop_.load(std::memory_order_relaxed)) return;
        fn_(task_, part);
        pending_.fetch_sub(1, std::memory_order_release);
    }
}

}  // namespace echosim

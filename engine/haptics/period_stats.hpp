// The haptic loop's timing, gathered on the loop's own thread without allocating: every period
// between two wake-ups goes into a histogram of its error against the nominal period (1 us bins up to
// 5 ms, one overflow bin), with the largest error and the deadlines missed (a wake-up later than the
// next tick's deadline), the latest a tick began after its deadline (what cyclictest calls latency,
// to compare with the machine's own floor), and the page faults the loop's thread took after its
// start. Read it once the loop has stopped, or copy it: it is plain data.
#pragma once

#include <array>
#include <cstdint>

namespace echosim::haptics {

// The latest tick of a spell, taken apart (issue 34: a tick once began 100 ms late where cyclictest
// beside it saw 22 ms at most), so that a stall names its part: the tick before it, piece by piece
// (its work could have overrun), then the wait for its deadline (a sleep the kernel ended late, or
// a spin that did not end), where the thread ran, whether it was switched out and how much CPU time
// it had meanwhile. Filled on the loop's thread without allocating, locking or a system call beyond
// one getrusage and two sched_getcpu a tick (the vDSO's).
struct WorstTick {
    static constexpr int kHistory = 16;
    double late_ms = -1;            // its start after its deadline [ms] (-1: no tick yet)
    std::int64_t tick = 0;          // its number (HapticSample::tick)
    double at_s = 0;                // its deadline on the loop's clock [s from the loop's start]
    double monotonic_s = 0;         // its wake-up on CLOCK_MONOTONIC [s] (std::chrono::steady_clock's), beside other records
    double spell_ms = 0;            // from the wake-up before to this one
    // the tick before it [us]: the bookkeeping at its wake-up (stats, getrusage), the device's read,
    // the force, the device's write, the hand-offs (probe command, sample), and after it (stats
    // published every 100 ticks)
    double before_us = 0, read_us = 0, force_us = 0, write_us = 0, handoff_us = 0, after_us = 0;
    // then the wait: whether it slept (false: the deadline had passed when the work ended), how long
    // after the time asked (deadline - spin) clock_nanosleep returned, and the spin to the deadline [us]
    bool slept = false;
    double sleep_late_us = 0;
    double spin_us = 0;
    int cpu_before = -1, cpu_after = -1;  // sched_getcpu() at the end of the tick before, and at the wake-up
    // the loop's thread from the wake-up before to this one (getrusage RUSAGE_THREAD): switched out
    // waiting (sleeping: 1 a tick) or preempted, and the CPU time it had [ms] (spell_ms less this is
    // the time it was not running: asleep, waiting for a CPU, or its vCPU stopped by the host)
    long voluntary_switches = -1, involuntary_switches = -1;
    double ran_ms = -1;
    // how late the ticks before it began [us], oldest first (the pattern that led to it)
    float late_before_us[kHistory] = {};
};

struct PeriodStats {
    static constexpr int kBins = 5000;  // 1 us each
    std::array<std::uint32_t, kBins + 1> error_us{};  // |period - nominal|, the last bin: 5 ms or more
    std::int64_t periods = 0;
    std::int64_t missed_deadlines = 0;
    double max_error_ms = 0;
    double max_tick_us = 0;  // the longest tick's work (device, force, hand-offs)
    double max_late_ms = 0;  // the latest a tick began after its deadline
    double window_max_late_ms = 0;  // the same since the loop's window was last restarted (HapticLoop::restart_window)
    // minor + major faults of the loop's thread since its start, after it pre-faulted its stack and
    // buffers (getrusage RUSAGE_THREAD; brought up to date every 100 ticks and at the end)
    std::int64_t page_faults = 0;
    // the latest tick since the window was last restarted (its late_ms is window_max_late_ms), taken apart
    WorstTick worst;

    void add_period(double period_ms, double nominal_ms);
    // the periods added since `earlier`, a copy of these stats taken before: its largest error is the
    // upper edge of its highest non-empty bin (at most this one's largest), its longest tick and latest
    // start unknown (0), its worst tick none
    PeriodStats since(const PeriodStats& earlier) const;
    // adds `other`'s periods to these
    void merge(const PeriodStats& other);
    // the error below which a fraction q of the periods fall [ms] (to the bin, 1 us); 0 with none
    double error_quantile_ms(double q) const;
};

}  // namespace echosim::haptics

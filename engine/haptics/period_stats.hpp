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

    void add_period(double period_ms, double nominal_ms);
    // the periods added since `earlier`, a copy of these stats taken before: its largest error is the
    // upper edge of its highest non-empty bin (at most this one's largest), its longest tick and latest
    // start unknown (0)
    PeriodStats since(const PeriodStats& earlier) const;
    // adds `other`'s periods to these
    void merge(const PeriodStats& other);
    // the error below which a fraction q of the periods fall [ms] (to the bin, 1 us); 0 with none
    double error_quantile_ms(double q) const;
};

}  // namespace echosim::haptics

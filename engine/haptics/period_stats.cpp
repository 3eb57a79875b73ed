#include "haptics/period_stats.hpp"

#include <algorithm>
#include <cmath>

namespace echosim::haptics {

void PeriodStats::add_period(double period_ms, double nominal_ms)
{
    const double err = std::abs(period_ms - nominal_ms);
    const double bin = std::floor(err * 1000.0);
    ++error_us[std::size_t(std::clamp(bin, 0.0, double(kBins)))];
    ++periods;
    max_error_ms = std::max(max_error_ms, err);
}

PeriodStats PeriodStats::since(const PeriodStats& earlier) const
{
    PeriodStats d;
    for (std::size_t i = 0; i < error_us.size(); ++i) {
        d.error_us[i] = error_us[i] - earlier.error_us[i];
        if (d.error_us[i] > 0) d.max_error_ms = std::min(double(i + 1) / 1000.0, max_error_ms);
    }
    d.periods = periods - earlier.periods;
    d.missed_deadlines = missed_deadlines - earlier.missed_deadlines;
    d.page_faults = page_faults - earlier.page_faults;
    return d;
}

void PeriodStats::merge(const PeriodStats& other)
{
    for (std::size_t i = 0; i < error_us.size(); ++i) error_us[i] += other.error_us[i];
    periods += other.periods;
    missed_deadlines += other.missed_deadlines;
    max_error_ms = std::max(max_error_ms, other.max_error_ms);
    max_tick_us = std::max(max_tick_us, other.max_tick_us);
    max_late_ms = std::max(max_late_ms, other.max_late_ms);
    window_max_late_ms = std::max(window_max_late_ms, other.window_max_late_ms);
    page_faults += other.page_faults;
    if (other.worst.late_ms > worst.late_ms) worst = other.worst;
}

double PeriodStats::error_quantile_ms(double q) const
{
    if (periods == 0) return 0.0;
    const double want = std::clamp(q, 0.0, 1.0) * double(periods);
    double seen = 0;
    for (std::size_t i = 0; i < error_us.size(); ++i) {
        seen += error_us[i];
        // the bin's upper edge, but never beyond the largest error seen
        if (seen >= want) return std::min(double(i + 1) / 1000.0, max_error_ms);
    }
    return max_error_ms;
}

}  // namespace echosim::haptics

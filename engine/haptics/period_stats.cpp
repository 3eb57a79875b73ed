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

#include "haptics/period_stats.hpp"

#include <gtest/gtest.h>

namespace echosim::haptics {
namespace {

// 1 ms nominal; errors of k us each, n times
void add(PeriodStats& s, double error_us, int n)
{
    for (int i = 0; i < n; ++i) s.add_period(1.0 + error_us * 1e-3, 1.0);
}

TEST(PeriodStats, QuantilesAreTheBinsUpperEdgesCappedByTheLargestError)
{
    PeriodStats s;
    add(s, 2.5, 990);   // bin 2: [2, 3) us
    add(s, 40.2, 9);    // bin 40
    add(s, 700.0, 1);   // bin 700 (or 699 from rounding): the largest
    EXPECT_EQ(s.periods, 1000);
    EXPECT_DOUBLE_EQ(s.error_quantile_ms(0.5), 0.003);
    EXPECT_DOUBLE_EQ(s.error_quantile_ms(0.99), 0.003);   // 990 of 1000 at or below 3 us
    EXPECT_DOUBLE_EQ(s.error_quantile_ms(0.995), 0.041);
    EXPECT_NEAR(s.error_quantile_ms(1.0), 0.700, 1e-9);    // the largest itself, not its bin's edge
    EXPECT_NEAR(s.max_error_ms, 0.700, 1e-9);
}

TEST(PeriodStats, SinceIsWhatWasAddedAfterTheCopyAndMergeAddsItBack)
{
    PeriodStats s;
    add(s, 5.5, 100);
    add(s, 300.5, 2);
    const PeriodStats earlier = s;
    add(s, 10.5, 50);
    add(s, 90.5, 1);
    ++s.missed_deadlines;

    const PeriodStats d = s.since(earlier);
    EXPECT_EQ(d.periods, 51);
    EXPECT_EQ(d.missed_deadlines, 1);
    EXPECT_EQ(d.error_us[10], 50u);
    EXPECT_EQ(d.error_us[90], 1u);
    EXPECT_EQ(d.error_us[5], 0u);
    EXPECT_EQ(d.error_us[300], 0u);
    // the largest error after the copy: its bin's upper edge (the 0.3 ms before the copy is not in it)
    EXPECT_DOUBLE_EQ(d.max_error_ms, 0.091);
    EXPECT_DOUBLE_EQ(d.error_quantile_ms(0.5), 0.011);

    PeriodStats sum = earlier;
    sum.merge(d);
    EXPECT_EQ(sum.periods, s.periods);
    EXPECT_EQ(sum.missed_deadlines, s.missed_deadlines);
    EXPECT_EQ(sum.error_us, s.error_us);
    EXPECT_DOUBLE_EQ(sum.error_quantile_ms(0.99), s.error_quantile_ms(0.99));
}

TEST(PeriodStats, NothingSinceIsEmpty)
{
    PeriodStats s;
    add(s, 20.5, 10);
    const PeriodStats d = s.since(s);
    EXPECT_EQ(d.periods, 0);
    EXPECT_EQ(d.max_error_ms, 0.0);
    EXPECT_EQ(d.error_quantile_ms(0.99), 0.0);
}

}  // namespace
}  // namespace echosim::haptics

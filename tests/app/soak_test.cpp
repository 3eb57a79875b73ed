// The soak's judgement (engine/app/soak.cpp) on made-up runs: the memory bounds after the warm-up,
// and which deadline bounds fail a run under each --deadlines choice. The command itself runs in
// cli.soak_short.
#include "app/soak.hpp"

#include <vector>

#include "app/haptics_demo.hpp"

#include <gtest/gtest.h>

namespace echosim::app {
namespace {

// one sample a second for `seconds`, from `base` MiB, rising `per_s` MiB a second, with a
// sawtooth of `wiggle` MiB (an allocator that grows and trims)
std::vector<SoakSample> samples(int seconds, double base, double per_s, double wiggle = 0)
{
    std::vector<SoakSample> out;
    for (int i = 0; i <= seconds; ++i) out.push_back({double(i), base + per_s * i + (i % 2 ? wiggle : 0.0)});
    return out;
}

SoakResult quiet_run()
{
    SoakResult r;
    r.samples = samples(120, 180, 0, 0.5);
    r.rss = judge_memory(r.samples, soak_warmup_s(120));
    r.haptic_p99_ms = 0.02;
    return r;
}

const SoakBound& find(const std::vector<SoakBound>& bounds, const std::string& name)
{
    for (const SoakBound& b : bounds)
        if (b.name == name) return b;
    throw std::logic_error("no bound " + name);
}

TEST(Soak, WarmUpIsTheScriptsFirstRoundOrAQuarterOfTheRunAtMostThirtySeconds)
{
    EXPECT_DOUBLE_EQ(round_trip_s(), 7.2);
    EXPECT_DOUBLE_EQ(soak_warmup_s(12), 7.2);
    EXPECT_DOUBLE_EQ(soak_warmup_s(40), 10);
    EXPECT_DOUBLE_EQ(soak_warmup_s(120), 30);
    EXPECT_DOUBLE_EQ(soak_warmup_s(600), 30);
}

TEST(Soak, FlatMemoryHoldsAndTheWarmUpIsLeftOut)
{
    // 40 MiB taken in the warm-up (pipelines, pools), then flat with a 0.5 MiB sawtooth
    std::vector<SoakSample> s = samples(120, 200, 0, 0.5);
    for (SoakSample& m : s)
        if (m.t_s < 10) m.rss_mib = 160 + 4 * m.t_s;
    const MemoryVerdict v = judge_memory(s, 30);
    EXPECT_DOUBLE_EQ(v.start_mib, 200);  // the sample at 30 s
    EXPECT_DOUBLE_EQ(v.end_mib, 200);    // 120 s: even
    EXPECT_DOUBLE_EQ(v.max_mib, 200.5);
    EXPECT_EQ(v.samples, 91);
    EXPECT_NEAR(v.growth_mib, 0, 1e-12);
    EXPECT_LT(std::abs(v.trend_mib), 0.1);
}

TEST(Soak, ASteadyLeakFailsTheTrendEvenWhenTheEndSamplesHideIt)
{
    // 6 MiB over the 90 s after the warm-up, but the start sample caught a 3 MiB spike and the
    // end sample a 3 MiB trim: end - start says 0
    std::vector<SoakSample> s = samples(120, 200, 6.0 / 90.0);
    s[30].rss_mib += 3;
    s[120].rss_mib -= 3;
    SoakResult r;
    r.samples = s;
    r.rss = judge_memory(r.samples, 30);
    EXPECT_NEAR(r.rss.growth_mib, 0, 1e-9);
    EXPECT_NEAR(r.rss.trend_mib, 6, 0.5);
    EXPECT_NEAR(r.rss.slope_mib_per_min, 4, 0.3);
    const std::vector<SoakBound> b = judge_soak(r, DeadlineCheck::strict);
    EXPECT_TRUE(find(b, "rss_growth").held);
    EXPECT_FALSE(find(b, "rss_trend").held);
}

TEST(Soak, GrowthOverTheBoundFails)
{
    SoakResult r;
    r.samples = samples(60, 200, 0);
    r.samples.back().rss_mib += kSoakGrowthBoundMib + 1;
    r.rss = judge_memory(r.samples, 15);
    r.bounds = judge_soak(r, DeadlineCheck::report);
    EXPECT_FALSE(find(r.bounds, "rss_growth").held);
    EXPECT_FALSE(r.passed());
}

TEST(Soak, ValidationAndMemoryAlwaysFailARunDeadlinesAsAsked)
{
    SoakResult r = quiet_run();
    r.bounds = judge_soak(r, DeadlineCheck::strict);
    EXPECT_TRUE(r.passed());

    r.validation_messages = 1;
    r.bounds = judge_soak(r, DeadlineCheck::report);
    EXPECT_FALSE(r.passed());
    EXPECT_TRUE(find(r.bounds, "validation_messages").enforced);
    r.validation_messages = 0;

    // a missed deadline: fails strict only; a p99 over 0.1 ms: fails strict and p99
    r.haptic_missed = 2;
    EXPECT_FALSE((r.bounds = judge_soak(r, DeadlineCheck::strict), r.passed()));
    EXPECT_TRUE((r.bounds = judge_soak(r, DeadlineCheck::p99), r.passed()));
    EXPECT_TRUE((r.bounds = judge_soak(r, DeadlineCheck::report), r.passed()));
    r.haptic_p99_ms = 0.25;
    EXPECT_FALSE((r.bounds = judge_soak(r, DeadlineCheck::p99), r.passed()));
    EXPECT_TRUE((r.bounds = judge_soak(r, DeadlineCheck::report), r.passed()));
    // reported, not hidden
    const SoakBound& p99 = find(r.bounds, "haptic_period_p99");
    EXPECT_FALSE(p99.held);
    EXPECT_FALSE(p99.enforced);
    EXPECT_DOUBLE_EQ(p99.limit, kSoakPeriodP99BoundMs);
}

TEST(Soak, DeadlineChecksByName)
{
    for (DeadlineCheck c : {DeadlineCheck::strict, DeadlineCheck::p99, DeadlineCheck::report}) EXPECT_EQ(parse_deadline_check(to_string(c)), c);
    EXPECT_THROW(parse_deadline_check("lenient"), std::invalid_argument);
}

TEST(Soak, ResidentMemoryIsReadFromProc)
{
    const double mib = resident_mib();
    EXPECT_GT(mib, 1.0);
    EXPECT_LT(mib, 1 << 20);
}

}  // namespace
}  // namespace echosim::app

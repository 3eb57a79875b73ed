#include "app/host_steal.hpp"

#include <gtest/gtest.h>

namespace echosim::app {
namespace {

TEST(HostSteal, IsTheEighthNumberOfProcStatsCpuLine)
{
    EXPECT_DOUBLE_EQ(*parse_host_steal_s("cpu  1251103 2 104838 315762 2759 0 357 11744 0 0\n", 100), 117.44);
    EXPECT_DOUBLE_EQ(*parse_host_steal_s("cpu  10 20 30 40 50 60 70 250", 250), 1.0);  // older kernels: no guest columns
    EXPECT_FALSE(parse_host_steal_s("cpu0 1251103 2 104838 315762 2759 0 357 11744 0 0", 100));  // one CPU's line
    EXPECT_FALSE(parse_host_steal_s("cpu  1 2 3 4 5 6 7", 100));  // no steal column
    EXPECT_FALSE(parse_host_steal_s("cpu  1 2 3 4 5 6 7 x", 100));
    EXPECT_FALSE(parse_host_steal_s("cpu  1 2 3 4 5 6 7 8", 0));
    EXPECT_FALSE(parse_host_steal_s("", 100));
    const std::optional<double> now = host_steal_s();  // Linux has had the column since 2.6.11
    ASSERT_TRUE(now);
    EXPECT_GE(*now, 0.0);
}

}  // namespace
}  // namespace echosim::app

// cyclictest beside the haptic loop (engine/app/cyclictest.cpp): its summary read from recorded
// output (rt-tests 2.4 on Debian 12), and the runs that give no figure say why instead of a number.
#include "app/cyclictest.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace echosim::app {
namespace {

// `cyclictest -m -p 89 -i 1000 -D 3 -q`, as root on the 2-core VM while the build ran
constexpr const char* kOneThread =
    "# /dev/cpu_dma_latency set to 0us\n"
    "T: 0 ( 5681) P:89 I:1000 C:   2978 Min:     21 Act:   39 Avg:   53 Max:    8421\n";
// the same with -t 2 (one thread per CPU): the larger Max of the two
constexpr const char* kTwoThreads =
    "# /dev/cpu_dma_latency set to 0us\n"
    "T: 0 ( 9120) P:89 I:1000 C:   4979 Min:     14 Act:   31 Avg:   38 Max:     512\n"
    "T: 1 ( 9121) P:88 I:1500 C:   3319 Min:     12 Act:   40 Avg:   41 Max:    1896\n";
// as user nobody: no real-time priority, no summary
constexpr const char* kRefused =
    "Unable to change scheduling policy!\n"
    "Probably missing capabilities, either run as root or increase RLIMIT_RTPRIO limits.\n";

TEST(Cyclictest, ItsMaxIsTheLargestOfItsThreadsSummaries)
{
    EXPECT_EQ(parse_cyclictest_max_us(kOneThread), 8421.0);
    EXPECT_EQ(parse_cyclictest_max_us(kTwoThreads), 1896.0);
    EXPECT_EQ(parse_cyclictest_max_us("T: 0 ( 1) P:89 I:1000 C: 5 Min: 1 Act: 2 Avg: 3 Max: 7"), 7.0);  // no newline at the end
    EXPECT_FALSE(parse_cyclictest_max_us(kRefused));
    EXPECT_FALSE(parse_cyclictest_max_us(""));
    EXPECT_FALSE(parse_cyclictest_max_us("# /dev/cpu_dma_latency set to 0us\n"));
    EXPECT_FALSE(parse_cyclictest_max_us("T: 0 ( 5681) P:89 I:1000 C:      0 Min: 21 Act: 39 Avg: 53 Max: x\n"));
    EXPECT_FALSE(parse_cyclictest_max_us("Max: 12\n"));  // not a thread's line
}

TEST(Cyclictest, EachThreadsMaxIsKeptByItsNumber)
{
    EXPECT_EQ(parse_cyclictest_maxima_us(kTwoThreads), (std::vector<double>{512.0, 1896.0}));
    EXPECT_EQ(parse_cyclictest_maxima_us(kOneThread), (std::vector<double>{8421.0}));
    EXPECT_TRUE(parse_cyclictest_maxima_us(kRefused).empty());
    // a thread whose line is missing is -1, not another's figure
    EXPECT_EQ(parse_cyclictest_maxima_us("T: 1 ( 9) P:89 I:1000 C: 5 Min: 1 Act: 2 Avg: 3 Max: 40\n"), (std::vector<double>{-1.0, 40.0}));
}

TEST(Cyclictest, NotInstalledSaysSoWithoutAFigure)
{
    Cyclictest run(1.0, "echosim-no-such-cyclictest", {0});
    const CyclictestResult r = run.finish();
    EXPECT_FALSE(r.max_ms);
    EXPECT_TRUE(r.cpus.empty());
    EXPECT_NE(r.note.find("not installed"), std::string::npos) << r.note;
    EXPECT_NE(r.note.find("rt-tests"), std::string::npos) << r.note;
    EXPECT_EQ(r.command, "echosim-no-such-cyclictest -m -p 89 -i 1000 -q -D 2 -t 1 -a 0 -d 0");
}

// A thread pinned on every CPU this process may use, not one left to wander (issue 34): the haptic
// loop is pinned to one CPU, and a lone thread at its priority is pushed to another whenever the loop
// runs, so it measured the floor of a CPU the loop never ran on.
TEST(Cyclictest, RunsAThreadPinnedOnEveryCpuThisProcessMayUse)
{
    const std::vector<int> cpus = allowed_cpus();
    ASSERT_FALSE(cpus.empty());
    EXPECT_TRUE(std::is_sorted(cpus.begin(), cpus.end()));
    std::string list;
    for (int c : cpus) list += (list.empty() ? "" : ",") + std::to_string(c);
    Cyclictest run(1.0, "echo");  // echo prints the arguments it was given
    const CyclictestResult r = run.finish(false);
    EXPECT_EQ(r.note, "cyclictest gave no figure: -m -p 89 -i 1000 -q -D 2 -t " + std::to_string(cpus.size()) + " -a " + list + " -d 0")
        << r.note;
}

TEST(Cyclictest, EachCpusFigureIsItsThreads)
{
    // a stand-in that prints two threads' summaries whatever it is asked, as `-t 2 -a 3,5` would
    char dir[] = "/tmp/echosim-cyclictest-XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    const std::string program = std::string(dir) + "/cyclictest";
    {
        std::ofstream out(program);
        out << "#!/bin/sh\nprintf '%s' '" << kTwoThreads << "'\n";
    }
    ASSERT_EQ(::chmod(program.c_str(), 0700), 0);
    Cyclictest run(1.0, program, {3, 5});
    const CyclictestResult r = run.finish(false);
    std::filesystem::remove_all(dir);
    ASSERT_TRUE(r.max_ms) << r.note;
    EXPECT_DOUBLE_EQ(*r.max_ms, 1.896);
    ASSERT_EQ(r.cpus.size(), 2u);
    EXPECT_DOUBLE_EQ(r.max_on(3).value_or(-1), 0.512);
    EXPECT_DOUBLE_EQ(r.max_on(5).value_or(-1), 1.896);
    EXPECT_FALSE(r.max_on(4));
}

TEST(Cyclictest, AProgramThatGivesNoSummaryIsNamedNotCounted)
{
    // echo prints its arguments and ends: a run with no thread summary (waited for, not interrupted:
    // a signal before it prints would leave nothing to read)
    Cyclictest run(1.0, "echo", {0, 1});
    const CyclictestResult r = run.finish(false);
    EXPECT_FALSE(r.max_ms);
    EXPECT_EQ(r.note, "cyclictest gave no figure: -m -p 89 -i 1000 -q -D 2 -t 2 -a 0,1 -d 0") << r.note;
}

}  // namespace
}  // namespace echosim::app

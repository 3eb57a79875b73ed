#include "core/fork_join.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace echosim {
namespace {

TEST(ForkJoin, EveryPartRunsOncePerRunOnItsOwnThread)
{
    ForkJoin team(3);
    ASSERT_EQ(team.parts(), 3);
    std::vector<int> runs(3, 0);
    std::vector<std::thread::id> ids(3);
    for (int i = 0; i < 2000; ++i)
        team.run([&](int part) {
            ++runs[std::size_t(part)];  // parts write disjoint data: no atomics needed
            ids[std::size_t(part)] = std::this_thread::get_id();
        });
    EXPECT_EQ(runs, std::vector<int>(3, 2000));
    EXPECT_EQ(ids[0], std::this_thread::get_id());  // the caller takes part 0
    EXPECT_EQ(std::set<std::thread::id>(ids.begin(), ids.end()).size(), 3u);
}

TEST(ForkJoin, PartsRunAtTheSameTime)
{
    // each part waits (up to 10 s) for the other to arrive: both see it only if they run at once
    ForkJoin team(2);
    std::atomic<int> arrived{0};
    std::vector<int> saw_both(2, 0);
    team.run([&](int part) {
        ++arrived;
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (arrived.load() < 2 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        saw_both[std::size_t(part)] = arrived.load() == 2;
    });
    EXPECT_EQ(saw_both, std::vector<int>(2, 1));
}

TEST(ForkJoin, WorkersWakeAfterSleeping)
{
    // between steps workers stop spinning and sleep; a run after a pause must still reach them
    ForkJoin team(2);
    for (int i = 0; i < 3; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        std::vector<int> ran(2, 0);
        team.run([&](int part) { ran[std::size_t(part)] = 1; });
        EXPECT_EQ(ran, std::vector<int>(2, 1));
    }
}

TEST(ForkJoin, ResultsAreSeenByTheCallerAfterTheRun)
{
    ForkJoin team(2);
    std::vector<long> data(100001);
    std::iota(data.begin(), data.end(), 0L);
    for (int i = 0; i < 200; ++i) {
        std::vector<long> partial(2, 0);
        team.run([&](int part) {
            const auto [begin, end] = part_range(data.size(), part, team.parts());
            for (std::size_t k = begin; k < end; ++k) partial[std::size_t(part)] += data[k];
        });
        ASSERT_EQ(partial[0] + partial[1], 100000L * 100001L / 2);
    }
}

TEST(ForkJoin, ATeamOfOneRunsInline)
{
    ForkJoin team(1);
    std::thread::id id;
    team.run([&](int part) {
        EXPECT_EQ(part, 0);
        id = std::this_thread::get_id();
    });
    EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(ForkJoin, PartRangesCoverEverythingOnce)
{
    for (std::size_t total : {0u, 1u, 7u, 225u, 50625u})
        for (int parts : {1, 2, 3, 8}) {
            std::size_t next = 0;
            for (int part = 0; part < parts; ++part) {
                const auto [begin, end] = part_range(total, part, parts);
                EXPECT_EQ(begin, next);
                EXPECT_LE(end - begin, total / std::size_t(parts) + 1);
                next = end;
            }
            EXPECT_EQ(next, total);
        }
}

TEST(ForkJoin, RejectsATeamOfNoneOrTooMany)
{
    EXPECT_THROW(ForkJoin(0), std::invalid_argument);
    EXPECT_THROW(ForkJoin(ForkJoin::kMaxParts + 1), std::invalid_argument);
}

}  // namespace
}  // namespace echosim

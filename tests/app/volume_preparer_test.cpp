// The cases' volumes made behind the window (app/volume_preparer.hpp), with a load of the test's
// own that reports its progress in steps and counts its calls: the wanted case made once and held,
// a pause that holds the making mid-way, another case wanted first, the background cases skipped
// when cached, a failure kept per case, and an end that stops a making under way.
#include <atomic>
#include <chrono>
#include <memory>
#include <set>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "app/volume_preparer.hpp"

namespace echosim {
namespace {

using app::VolumePreparer;
using namespace std::chrono_literals;

exam::Scenario named(const std::string& id)
{
    exam::Scenario s;
    s.id = id;
    return s;
}

// A load in `steps` progress reports `pause` apart; the volume's description is the case's id.
struct FakeLoad {
    int steps = 20;
    std::chrono::milliseconds pause = 2ms;
    std::set<std::string> failing;
    std::atomic<int> calls{0}, finished{0}, stopped{0};
    std::mutex mutex;
    std::vector<std::string> order;  // the cases whose load began, in order

    VolumePreparer::Load load()
    {
        return [this](const exam::Scenario& c, const VolumePreparer::Progress& progress) {
            ++calls;
            {
                std::lock_guard lock(mutex);
                order.push_back(c.id);
            }
            if (failing.count(c.id)) throw std::runtime_error("cannot write the volume cache for " + c.id);
            try {
                for (int i = 0; i < steps; ++i) {
                    progress("imaging", double(i) / steps);
                    std::this_thread::sleep_for(pause);
                }
            } catch (...) {
                ++stopped;
                throw;
            }
            ++finished;
            app::VolumePair pair;
            pair.volume = std::make_shared<io::Volume>();
            pair.description = c.id;
            return pair;
        };
    }
};

// polls `done` for up to 20 s (a loaded machine)
template <class F>
bool eventually(F done)
{
    for (int i = 0; i < 4000; ++i) {
        if (done()) return true;
        std::this_thread::sleep_for(5ms);
    }
    return done();
}

TEST(VolumePreparer, MakesTheWantedCaseOnceAndHoldsIt)
{
    FakeLoad fake;
    VolumePreparer p(fake.load(), [](const exam::Scenario&) { return false; }, 0);
    EXPECT_EQ(p.status("a").state, VolumePreparer::State::waiting);
    EXPECT_FALSE(p.take("a"));
    fake.pause = 20ms;  // long enough to be seen mid-way
    p.want(named("a"));
    ASSERT_TRUE(eventually([&] { return p.status("a").state == VolumePreparer::State::making && p.status("a").done > 0; }));
    EXPECT_EQ(p.status("a").stage, "imaging");
    ASSERT_TRUE(eventually([&] { return p.status("a").state == VolumePreparer::State::ready; }));
    ASSERT_TRUE(p.take("a"));
    EXPECT_EQ(p.take("a")->description, "a");  // held: taken again by a runner rebuilt
    p.want(named("a"));                        // wanted again: not made again
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(fake.calls.load(), 1);
    EXPECT_EQ(p.status("b").state, VolumePreparer::State::waiting);
}

TEST(VolumePreparer, APauseHoldsTheMakingMidWay)
{
    FakeLoad fake;
    VolumePreparer p(fake.load(), [](const exam::Scenario&) { return false; }, 0);
    p.want(named("a"));
    ASSERT_TRUE(eventually([&] { return p.status("a").done >= 0.2; }));
    p.pause(true);
    // the step under way ends and its report waits: the progress stands still
    ASSERT_TRUE(eventually([&] {
        const double before = p.status("a").done;
        std::this_thread::sleep_for(200ms);
        return p.status("a").done == before;
    }));
    const double held = p.status("a").done;
    std::this_thread::sleep_for(200ms);  // 100 steps' worth
    EXPECT_EQ(p.status("a").done, held);
    EXPECT_EQ(p.status("a").state, VolumePreparer::State::making);
    EXPECT_LT(held, 1.0);
    p.pause(false);
    ASSERT_TRUE(eventually([&] { return p.status("a").state == VolumePreparer::State::ready; }));
    EXPECT_EQ(fake.calls.load(), 1);
}

TEST(VolumePreparer, TheWantedCaseGoesBeforeTheBackgroundsWhichIsMadeLater)
{
    FakeLoad fake;
    fake.steps = 200;  // two steps' 2 ms: the background making lasts long enough to be preempted
    // "cached" is in the cache already: skipped, counted as made
    VolumePreparer p(fake.load(), [](const exam::Scenario& c) { return c.id == "cached"; }, 0);
    p.also_make({named("cached"), named("bg")});
    ASSERT_TRUE(eventually([&] { return p.status("bg").state == VolumePreparer::State::making; }));
    EXPECT_EQ(p.made(), std::make_pair(1, 2));
    p.want(named("w"));
    ASSERT_TRUE(eventually([&] { return p.status("w").state == VolumePreparer::State::ready; }));
    EXPECT_EQ(fake.stopped.load(), 1);  // bg's making stopped for w's
    ASSERT_TRUE(eventually([&] { return p.made().first == 2; }));
    EXPECT_EQ(fake.finished.load(), 2);
    std::lock_guard lock(fake.mutex);
    EXPECT_EQ(fake.order, (std::vector<std::string>{"bg", "w", "bg"}));
    EXPECT_EQ(p.take("w")->description, "w");
    EXPECT_FALSE(p.take("bg"));  // made for the cache, not held
}

TEST(VolumePreparer, AFailureIsKeptForItsCaseAndTheOthersGoOn)
{
    FakeLoad fake;
    fake.failing = {"bad"};
    VolumePreparer p(fake.load(), [](const exam::Scenario&) { return false; }, 0);
    p.want(named("bad"));
    ASSERT_TRUE(eventually([&] { return p.status("bad").state == VolumePreparer::State::failed; }));
    EXPECT_EQ(p.status("bad").error, "cannot write the volume cache for bad");
    p.want(named("good"));
    ASSERT_TRUE(eventually([&] { return p.status("good").state == VolumePreparer::State::ready; }));
    p.want(named("bad"));  // not tried again in this run
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(fake.calls.load(), 2);
}

// No cache folder ($HOME and $XDG_CACHE_HOME unset): the cache cannot be asked, a background case
// is made all the same, and its failure (the making's own) is kept, never thrown on the worker.
TEST(VolumePreparer, ACacheThatCannotBeAskedIsNoCache)
{
    FakeLoad fake;
    fake.failing = {"no-home"};
    VolumePreparer p(fake.load(), [](const exam::Scenario&) -> bool { throw std::runtime_error("no cache folder"); }, 0);
    p.also_make({named("no-home"), named("fine")});
    ASSERT_TRUE(eventually([&] { return p.made().first == 1 && p.status("no-home").state == VolumePreparer::State::failed; }));
    EXPECT_EQ(fake.finished.load(), 1);
}

TEST(VolumePreparer, TheEndStopsAMakingUnderWay)
{
    FakeLoad fake;
    fake.steps = 100000;  // minutes
    {
        VolumePreparer p(fake.load(), [](const exam::Scenario&) { return false; }, 0);
        p.want(named("a"));
        ASSERT_TRUE(eventually([&] { return p.status("a").done > 0; }));
    }
    EXPECT_EQ(fake.stopped.load(), 1);
    EXPECT_EQ(fake.finished.load(), 0);  // 200 s of steps: the destructor did not wait for them
}

}  // namespace
}  // namespace echosim

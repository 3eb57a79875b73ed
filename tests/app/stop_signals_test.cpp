// The hand-off from SIGINT/SIGTERM to a command's loop (engine/app/stop_signals.cpp): a signal
// while a StopSignals lives is a request, not the end of the process; the first one is kept; the
// second would end the process as usual; the handlers it replaced come back. The commands'
// stop in order is checked end to end in cli.soak_sigterm.
#include "app/stop_signals.hpp"

#include <csignal>
#include <stdexcept>

#include <gtest/gtest.h>

namespace echosim::app {
namespace {

void (*handler_of(int signal))(int)
{
    struct sigaction now {};
    sigaction(signal, nullptr, &now);
    return now.sa_handler;
}

extern "C" void ours(int) {}

TEST(StopSignals, ASignalIsARequestAndTheFirstOneIsKept)
{
    const StopSignals stop;
    EXPECT_EQ(stop.requested(), 0);
    ASSERT_EQ(std::raise(SIGTERM), 0);  // the test lives on: the handler only sets the flag
    EXPECT_EQ(stop.requested(), SIGTERM);
    EXPECT_EQ(StopSignals::exit_code(stop.requested()), 143);
    EXPECT_STREQ(StopSignals::name(stop.requested()), "SIGTERM");
    // caught once: a second signal of either kind would end the process (not raised here)
    EXPECT_EQ(handler_of(SIGTERM), SIG_DFL);
    EXPECT_EQ(handler_of(SIGINT), SIG_DFL);
    EXPECT_EQ(StopSignals::exit_code(SIGINT), 130);
}

// A signal ignored when the command starts (nohup, a script's background job) stays ignored.
TEST(StopSignals, LeavesAnIgnoredSignalIgnored)
{
    std::signal(SIGTERM, SIG_IGN);
    {
        const StopSignals stop;
        EXPECT_EQ(handler_of(SIGTERM), SIG_IGN);
        EXPECT_NE(handler_of(SIGINT), SIG_IGN);
        ASSERT_EQ(std::raise(SIGTERM), 0);
        EXPECT_EQ(stop.requested(), 0);
    }
    EXPECT_EQ(handler_of(SIGTERM), SIG_IGN);
    std::signal(SIGTERM, SIG_DFL);
}

TEST(StopSignals, PutsBackTheHandlersItReplacedAndStartsWithoutARequest)
{
    std::signal(SIGINT, ours);
    std::signal(SIGTERM, ours);
    {
        const StopSignals stop;
        EXPECT_NE(handler_of(SIGINT), &ours);
        EXPECT_EQ(stop.requested(), 0) << "a request left by an earlier test";
        ASSERT_EQ(std::raise(SIGINT), 0);
        EXPECT_EQ(stop.requested(), SIGINT);
        EXPECT_THROW(StopSignals second, std::logic_error);
    }
    EXPECT_EQ(handler_of(SIGINT), &ours);
    EXPECT_EQ(handler_of(SIGTERM), &ours);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    const StopSignals again;  // one at a time, not one ever
    EXPECT_EQ(again.requested(), 0);
}

}  // namespace
}  // namespace echosim::app

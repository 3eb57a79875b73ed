#include "app/stop_signals.hpp"

#include <atomic>
#include <csignal>
#include <stdexcept>

namespace echosim::app {
namespace {

// The hand-off (stop_signals.hpp): written by the handler, read by the command's loop.
std::atomic<int> g_requested{0};
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only touch a lock-free atomic");
// Whether a StopSignals lives, and the handlers it replaced: the constructing thread's alone.
bool g_installed = false;
struct sigaction g_previous_int {}, g_previous_term {};

extern "C" void on_stop_signal(int signal)
{
    int none = 0;
    g_requested.compare_exchange_strong(none, signal, std::memory_order_relaxed);  // the first one wins
}

}  // namespace

StopSignals::StopSignals()
{
    if (g_installed) throw std::logic_error("StopSignals: one is already installed");
    g_requested.store(0);
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART | SA_RESETHAND;
    sigaction(SIGINT, &action, &g_previous_int);
    sigaction(SIGTERM, &action, &g_previous_term);
    g_installed = true;
}

StopSignals::~StopSignals()
{
    sigaction(SIGINT, &g_previous_int, nullptr);
    sigaction(SIGTERM, &g_previous_term, nullptr);
    g_installed = false;
}

int StopSignals::requested() const { return g_requested.load(std::memory_order_relaxed); }

const char* StopSignals::name(int signal)
{
    switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
    }
}

}  // namespace echosim::app

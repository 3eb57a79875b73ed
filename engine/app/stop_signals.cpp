#include "app/stop_signals.hpp"

#include <atomic>
#include <csignal>
#include <stdexcept>

namespace echosim::app {
namespace {

// The hand-off (stop_signals.hpp): written by the handler, read by the command's loop.
std::atomic<int> g_requested{0};
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only touch a lock-free atomic");
// Whether a StopSignals lives, and the handlers it replaced: the constructing thread's alone
// (written before the handler is installed, only read by it).
bool g_installed = false;
bool g_caught_int = false, g_caught_term = false;  // not when the signal was ignored on entry (nohup)
struct sigaction g_previous_int {}, g_previous_term {};

extern "C" void on_stop_signal(int signal)
{
    int none = 0;
    g_requested.compare_exchange_strong(none, signal, std::memory_order_relaxed);  // the first one wins
    // a second signal, of either kind, ends the process at once (sigaction is async-signal-safe)
    struct sigaction fallback {};
    fallback.sa_handler = SIG_DFL;
    sigemptyset(&fallback.sa_mask);
    if (g_caught_int) sigaction(SIGINT, &fallback, nullptr);
    if (g_caught_term) sigaction(SIGTERM, &fallback, nullptr);
}

// Whether `signal` was ignored when we came (nohup, a script's background job): it stays so.
bool ignored(int signal)
{
    struct sigaction now {};
    return sigaction(signal, nullptr, &now) == 0 && now.sa_handler == SIG_IGN;
}

}  // namespace

StopSignals::StopSignals()
{
    if (g_installed) throw std::logic_error("StopSignals: one is already installed");
    g_requested.store(0);
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    g_caught_int = !ignored(SIGINT);
    g_caught_term = !ignored(SIGTERM);
    if (g_caught_int) sigaction(SIGINT, &action, &g_previous_int);
    if (g_caught_term) sigaction(SIGTERM, &action, &g_previous_term);
    g_installed = true;
}

StopSignals::~StopSignals()
{
    if (g_caught_int) sigaction(SIGINT, &g_previous_int, nullptr);
    if (g_caught_term) sigaction(SIGTERM, &g_previous_term, nullptr);
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

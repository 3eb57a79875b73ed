// SIGINT and SIGTERM as a request to stop in order (issue 34), for every command that drives a
// session in real time (`run`, `soak`, and `exam` when it comes): while a StopSignals lives, either
// signal no longer ends the process; it only asks the command's loop to end. The loop looks at
// requested() once a frame and, when it is set, leaves the way it would at its end: the session
// stops (the haptic loop first, which sends the device a zero force: haptics/haptic_loop.hpp), the
// command writes its records and prints its summary, and it exits with 128 + the signal's number
// (130 for SIGINT, 143 for SIGTERM), as a shell reports a process the signal ended.
//
// The one hand-off, and the project's one piece of global state (STYLE.md: a signal handler can
// reach nothing else): the handler stores the signal's number in a lock-free std::atomic<int>, an
// async-signal-safe store, and puts both signals back to their default (sigaction, also
// async-signal-safe). Any thread may take the signal.
//
// A second signal is not caught: if stopping in order hangs, a second Ctrl-C or SIGTERM (either
// after either) ends the process at once, as it would have without us. A signal ignored when we
// come (nohup, a script's background job) is left ignored. Handlers are installed with
// SA_RESTART, so the rest of the program (file reads, the network) never sees EINTR because of them.
#pragma once

namespace echosim::app {

class StopSignals {
public:
    // Catches SIGINT and SIGTERM from now on; a request left from an earlier StopSignals is
    // cleared. One at a time: a second while one lives throws std::logic_error.
    StopSignals();
    // Puts back the handlers it replaced (a signal that comes after takes its usual course).
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

    // 0 while none came, else the number of the first signal that came (SIGINT, SIGTERM).
    int requested() const;

    // "SIGINT", "SIGTERM" (else "a signal")
    static const char* name(int signal);
    // The exit status of a command the signal stopped: 128 + its number.
    static int exit_code(int signal) { return 128 + signal; }
};

}  // namespace echosim::app

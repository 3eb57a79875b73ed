// `cyclictest` (Debian's rt-tests) run beside the haptic loop: the machine's own floor for a 1 kHz
// real-time thread, measured under the same load in the same spell (`echosim bench haptics`,
// `echosim soak`), so the loop's worst late tick is read against what this machine allows at all,
// not against a hope. Run as `cyclictest -m -p 89 -i 1000 -q -D <s>`: its memory locked, one thread
// at the haptic loop's priority (SCHED_FIFO 89: the maximum less 10), woken every 1000 us; `-q`
// prints one summary line per thread at the end, whose `Max:` is its latest wake-up [us].
//
// Started with posix_spawn (no fork: a fork would make every page of this process copy-on-write,
// and the haptic loop's next write to each a page fault). Never throws: where it is not installed
// or refuses to run (no real-time priority), the result says so and has no figure.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <sys/types.h>

namespace echosim::app {

inline constexpr const char* kCyclictest = "cyclictest";
inline constexpr int kCyclictestPriority = 89;
inline constexpr int kCyclictestIntervalUs = 1000;

struct CyclictestResult {
    std::optional<double> max_ms;  // the latest wake-up of its threads [ms]; none when it did not run
    std::string note;              // why there is no figure ("" when there is one)
    std::string command;           // the command line run
};

// The largest `Max:` of the thread summary lines ("T: 0 ( 5681) P:89 I:1000 C: 2978 Min: 21 Act: 39
// Avg: 53 Max: 8421") in `-q` output [us]; nullopt when there is none.
std::optional<double> parse_cyclictest_max_us(std::string_view output);

class Cyclictest {
public:
    // Starts it now for at most `seconds` (rounded up, plus one: finish() ends it on time).
    explicit Cyclictest(double seconds, const std::string& program = kCyclictest);
    ~Cyclictest();  // ends it, if it still runs
    Cyclictest(const Cyclictest&) = delete;
    Cyclictest& operator=(const Cyclictest&) = delete;

    // Ends it now (SIGINT: it prints its summary as at the end of its duration; `interrupt` false:
    // at the end of its duration), waits, and reads it.
    CyclictestResult finish(bool interrupt = true);

private:
    pid_t pid_ = -1;
    int out_ = -1;  // its stdout and stderr, read at the end (a -q run writes a few lines)
    CyclictestResult result_;
};

}  // namespace echosim::app

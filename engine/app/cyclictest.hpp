// `cyclictest` (Debian's rt-tests) run beside the haptic loop: the machine's own floor for a 1 kHz
// real-time thread, measured under the same load in the same spell (`echosim bench haptics`,
// `echosim soak`), so the loop's worst late tick is read against what this machine allows at all,
// not against a hope. Run as `cyclictest -m -p 89 -i 1000 -q -D <s> -t <n> -a <cpus> -d 0`: its
// memory locked, one thread on each CPU this process may use (pinned there, the n-th thread on the
// n-th CPU), at the haptic loop's priority (SCHED_FIFO 89: the maximum less 10), each woken every
// 1000 us; `-q` prints one summary line per thread at the end, whose `Max:` is its latest wake-up [us].
//
// One thread on every CPU, not one left to wander (issue 34): the haptic loop is pinned to one CPU,
// and a lone cyclictest thread at its priority is pushed off that CPU whenever the loop runs there
// (the scheduler spreads real-time threads), so it measured the other CPU's floor, not the loop's:
// a soak's loop once started a tick 100 ms late where such a thread saw 22 ms at most, and in a
// 2-minute soak measured both ways the loop's latest tick (30.499 ms) was the pinned thread's on its
// CPU (30.492 ms) while the wandering one saw 28.305 ms. The machine's floor is the worst of its
// CPUs (max_ms); the loop's own CPU's is there too (CyclictestResult::max_on).
//
// Started with posix_spawn (no fork: a fork would make every page of this process copy-on-write,
// and the haptic loop's next write to each a page fault). Never throws: where it is not installed
// or refuses to run (no real-time priority), the result says so and has no figure.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>
#include <sys/types.h>

namespace echosim::app {

inline constexpr const char* kCyclictest = "cyclictest";
inline constexpr int kCyclictestPriority = 89;
inline constexpr int kCyclictestIntervalUs = 1000;

struct CyclictestCpu {
    int cpu = -1;
    double max_ms = 0;  // the latest wake-up of the thread pinned to it [ms]
};

struct CyclictestResult {
    std::optional<double> max_ms;  // the latest wake-up of its threads, all CPUs [ms]; none when it did not run
    std::vector<CyclictestCpu> cpus;  // each CPU's thread's (empty when it did not run)
    // the thread's on `cpu` [ms]; none where no thread ran there
    std::optional<double> max_on(int cpu) const;
    std::string note;              // why there is no figure ("" when there is one)
    std::string command;           // the command line run
};

// The largest `Max:` of the thread summary lines ("T: 0 ( 5681) P:89 I:1000 C: 2978 Min: 21 Act: 39
// Avg: 53 Max: 8421") in `-q` output [us]; nullopt when there is none.
std::optional<double> parse_cyclictest_max_us(std::string_view output);
// Each thread summary line's `Max:` [us], by its thread number (`T: n`; -1 where a number is
// missing or not one; lines that are not a thread's summary are skipped).
std::vector<double> parse_cyclictest_maxima_us(std::string_view output);

// The CPUs this process may run on (sched_getaffinity), ascending; {} where they cannot be read.
std::vector<int> allowed_cpus();

class Cyclictest {
public:
    // Starts it now for at most `seconds` (rounded up, plus one: finish() ends it on time), one thread
    // on each of `cpus` (none given: allowed_cpus(); none readable: one thread, unpinned).
    explicit Cyclictest(double seconds, const std::string& program = kCyclictest, std::vector<int> cpus = {});
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
    std::vector<int> cpus_;  // the n-th thread's CPU
};

}  // namespace echosim::app

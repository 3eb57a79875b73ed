// `echosim soak` (issue 13): a long scripted session, headless, with every part that runs in the
// simulator running at once, to show that nothing grows, complains or falls behind over time:
//   - the probe: a scripted device playing the Fig. 8 slide there and back, looped (it comes down
//     onto the thigh, presses 6 mm in, slides across it, lifts, and does the same the other way);
//   - the 1 kHz haptic loop on its own thread (SCHED_FIFO where permitted), the physics thread
//     stepping the 2,500-node patch at 1 kHz, both on the real-time clock, as in `echosim run`;
//   - on the calling thread, frame after frame: the patch deformed from the latest physics step,
//     the echographic image (deform, slice, post) made on the GPU from the same step, and the
//     scene with the image beside it rendered offscreen and read back, with the Khronos validation
//     layer always on: the runner's offscreen configuration on the real-time clock
//     (runner/runner.hpp), the sampling below its observer.
// Resident memory (/proc/self/statm) is sampled once a second. The run is judged by the bounds
// below (the help text, the JSON and the README quote them): memory after a warm-up, validation
// messages, and the haptic loop's deadlines (DESIGN.md §5).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "app/volume_source.hpp"
#include "gpu/context.hpp"
#include "haptics/period_stats.hpp"
#include "runner/runner.hpp"

namespace echosim::app {

// The warm-up before the start figure: the script's first round (7.2 s: every state the probe
// goes through, lifted, pressing, sliding each way, drawn at least once, so every pipeline and
// buffer has been made) or a quarter of the run, whichever is longer, at most 30 s.
inline constexpr double kSoakWarmupFraction = 0.25;
inline constexpr double kSoakWarmupMaxS = 30.0;
inline constexpr double kSoakMinSeconds = 10.0;  // a run has samples after its warm-up
// Resident memory at the end minus at the end of the warm-up [MiB], at most.
inline constexpr double kSoakGrowthBoundMib = 4.0;
// The rise of the least-squares line through the samples after the warm-up, over their span [MiB],
// at most: a steady leak that noise at the two end samples would hide.
inline constexpr double kSoakTrendBoundMib = 4.0;
// The haptic loop's period error, 99th percentile [ms], at most (DESIGN.md §5); and no missed
// deadline (a wake-up more than one period, 1 ms, late).
inline constexpr double kSoakPeriodP99BoundMs = 0.1;
// The seconds in which the host took no CPU time from this machine (below), at least, for their
// period error to be judged: fewer, and the run says it could not judge it.
inline constexpr double kSoakMinStealFreeS = 10.0;

// Which of the deadline bounds fail the run (memory and validation always do):
//   strict: all three: the period error's 99th percentile over the whole run and over the seconds
//           free of host steal, and no missed deadline (a run by hand on a quiet machine);
//   p99:    the 99th percentile over the seconds free of host steal; the whole run's and the missed
//           deadlines are reported (CI: a shared VM's hypervisor runs other guests on our CPUs, the
//           "steal" of /proc/stat, and stalls a vCPU for up to tens of milliseconds, which no
//           priority inside the VM prevents; we judge the loop where it had the CPUs);
//   report: none, reported only (tests on a loaded machine, without real-time priority).
enum class DeadlineCheck { strict, p99, report };
DeadlineCheck parse_deadline_check(const std::string& name);  // throws std::invalid_argument
const char* to_string(DeadlineCheck check);

double soak_warmup_s(double seconds);

// Taken once a second.
struct SoakSample {
    double t_s = 0;      // since the run began
    double rss_mib = 0;  // resident set [MiB]
    long long frames = 0;         // drawn so far
    long long haptic_missed = 0;  // the haptic loop's missed deadlines so far (when they happened)
    double host_steal_s = -1;     // the host's steal so far, all CPUs [s]; -1 where it cannot be read
};

// Resident memory of this process now [MiB] (/proc/self/statm); 0 where it cannot be read.
double resident_mib();

struct MemoryVerdict {
    double start_mib = 0;  // the first sample at or after the warm-up
    double end_mib = 0;    // the last sample
    double max_mib = 0;    // over the whole run, warm-up included
    double growth_mib = 0; // end - start
    double trend_mib = 0;  // the fitted line's rise from the start sample's time to the end's
    double slope_mib_per_min = 0;
    int samples = 0;       // from the start sample on
};
MemoryVerdict judge_memory(std::span<const SoakSample> samples, double warmup_s);

struct SoakBound {
    // rss_growth, rss_trend, validation_messages, haptic_period_p99, haptic_period_p99_steal_free,
    // haptic_missed_deadlines
    std::string name;
    double value = 0, limit = 0;  // held when value <= limit
    std::string unit;
    bool held = false;
    bool enforced = true;  // a bound that does not hold fails the run
    std::string note;      // why an enforceable bound was not judged, "" otherwise
};

struct SoakResult {
    double requested_s = 0, seconds = 0, warmup_s = 0;
    bool session_started = false;  // false: stopped while the volume was made, nothing ran
    std::string device;  // the Vulkan device
    std::uint32_t width = 0, height = 0;
    long long frames = 0;
    long long physics_steps = 0, physics_late_steps = 0;
    long long haptic_ticks = 0;
    std::string haptic_priority;  // "SCHED_FIFO, CPUs kept awake", or what the loop lacks and why
    bool haptic_cpus_awake = false;  // the loop held its wake-latency request (haptics/cpu_wake_latency.hpp)
    double haptic_p50_ms = 0, haptic_p99_ms = 0, haptic_max_ms = 0;
    long long haptic_missed = 0;
    // the loop's latest tick (its start after its deadline) over the run, cyclictest's spell [ms], its
    // thread's page faults after its start, whether it held the process's memory locked, and the CPU
    // it was pinned to (-1: none)
    double haptic_late_max_ms = 0;
    // that tick taken apart (haptics/period_stats.hpp): what the loop was doing, where, for how long
    haptics::WorstTick haptic_worst;
    long long page_faults = 0;
    bool haptic_memory_locked = false;
    int haptic_cpu = -1;
    // the machine's floor in the same spell (app/cyclictest.hpp): cyclictest's latest wake-up [ms],
    // none with the reason where it could not run
    std::optional<double> cyclictest_max_ms;
    std::string cyclictest_note;
    // its thread on the loop's CPU (the like-for-like floor; none where the loop was not pinned) and
    // each CPU's (app/cyclictest.hpp: one thread pinned on each)
    std::optional<double> cyclictest_loop_cpu_max_ms;
    std::vector<std::pair<int, double>> cyclictest_cpus;
    // the host's steal over the run, all CPUs [s] (-1: cannot be read); the sampled seconds in which
    // it took nothing (all of them where it cannot be read), and the haptic periods of those seconds
    double host_steal_s = -1;
    double steal_free_s = 0;
    long long haptic_steal_free_periods = 0;
    double haptic_steal_free_p99_ms = 0;
    std::uint32_t validation_messages = 0;  // counted until the device was destroyed (leaks included)
    std::vector<SoakSample> samples;
    MemoryVerdict rss;
    DeadlineCheck deadlines = DeadlineCheck::strict;
    std::vector<SoakBound> bounds;
    // the signal that ended the run before its time (app/stop_signals.hpp), 0 when it ran to its end
    int stopped_by_signal = 0;

    bool passed() const;
};

// The bounds of a finished run, judged (`r.rss` already judged).
std::vector<SoakBound> judge_soak(const SoakResult& r, DeadlineCheck deadlines);

struct SoakProgress {
    double t_s = 0, seconds = 0;
    long long frames = 0;
    double rss_mib = 0;
    long long haptic_missed = 0;
};

struct SoakOptions {
    double seconds = 120;
    gpu::ContextOptions gpu;  // validation is turned on whatever it says
    std::uint32_t width = 1280, height = 720;
    DeadlineCheck deadlines = DeadlineCheck::strict;
    std::function<void(const SoakProgress&)> progress;  // about every tenth of the run
    // Looked at once a frame: a signal's number (app/stop_signals.hpp) ends the run there, in order
    // (the session stopped, the device sent a zero force, the run judged as far as it went); 0 goes on.
    std::function<int()> stop_requested;
    // The echographic volume; none (the default): the healthy case's, made coarse (0.6 mm) for the run.
    VolumePair volumes;
    // More observers of the runner the soak is a configuration of (runner/runner.hpp): tests count
    // its steps.
    std::vector<std::shared_ptr<runner::Observer>> observers;
};

// Runs the soak (a few seconds of set-up, then `seconds` of session, or until stop_requested says
// otherwise: a request while its own volume is made ends it there, before any session, and one
// later in set-up at its first frame) and judges it. Throws what set-up
// throws (no Vulkan device, no validation layer).
SoakResult run_soak_session(const SoakOptions& options);

// The report as JSON text (README "Soak").
std::string soak_json(const SoakResult& r);

}  // namespace echosim::app

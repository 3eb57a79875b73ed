#include "app/soak.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/cyclictest.hpp"
#include "app/default_scene.hpp"
#include "app/haptics_demo.hpp"
#include "app/host_steal.hpp"
#include "app/stop_signals.hpp"
#include "app/volume_source.hpp"
#include "device/scripted_device.hpp"
#include "echo/case_volume.hpp"
#include "runner/runner.hpp"

namespace echosim::app {
namespace {

// A stop asked for while the volume is made (SoakOptions::stop_requested): its signal.
struct StoppedInSetUp {
    int signal = 0;
};

// The image's volume: the healthy case made as `echosim run` makes it, but coarser (0.6 mm voxels
// from 60 frames of 0.3 mm pixels), so it takes seconds, not the half minute of the 0.4 mm one; its content
// does not change what a frame costs in memory. Those seconds are tens under a sanitizer, so a
// stop asked for meanwhile is looked at between chunks of a few frames (and the hole filling's
// steps) and ends the making there: throws StoppedInSetUp.
VolumePair soak_volume(const scene::LegModel& leg, const std::function<int()>& stop_requested)
{
    // frames 75 mm deep, not the cases' 95: the soak's image stays the scanner's first 50 mm (pressed 25)
    echo::CaseVolumeOptions coarse{.voxel_mm = 0.6, .frames = 60, .pixel_mm = 0.3, .depth_mm = 75.0};
    coarse.chunk_frames = 6;
    const auto look = [&](const std::string&, double) {
        if (const int signal = stop_requested ? stop_requested() : 0) throw StoppedInSetUp{signal};
    };
    echo::CaseVolume made = echo::make_case_volume(leg, echo::Case::healthy, coarse, look);
    return {std::make_shared<const io::Volume>(std::move(made.volume)), std::make_shared<const io::Volume>(std::move(made.labels)),
            "the healthy case at 0.6 mm"};
}

SoakBound bound(const char* name, double value, double limit, const char* unit, bool enforced)
{
    return {name, value, limit, unit, value <= limit, enforced};
}

// The soak's observer: before each step, a sample once a second (resident memory, frames, the
// haptic loop's missed deadlines, the host's steal; the haptic periods of the seconds free of
// steal merged into `steal_free`) and progress about every tenth of the run; the run ends, with a
// last sample, when its time is up or a stop is asked for (a signal). Counts the frames drawn.
class SoakSampler final : public runner::Observer {
public:
    SoakSampler(const SoakOptions& o, SoakResult& r, haptics::HapticLoop& loop, haptics::PeriodStats& steal_free)
        : o_(o), r_(r), loop_(loop), steal_free_(steal_free), start_(std::chrono::steady_clock::now()),
          progress_every_(std::max(5.0, 0.1 * o.seconds)), next_progress_(progress_every_)
    {
    }

    bool should_stop() override
    {
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        // a stop asked for (a signal) ends the run as its time would: a last sample, then out
        const int signal = o_.stop_requested ? o_.stop_requested() : 0;
        const bool end = t >= o_.seconds || signal != 0;
        if (t >= next_sample_ || end) {
            const haptics::PeriodStats h = loop_.stats();
            const std::optional<double> steal = host_steal_s();
            if (r_.samples.empty()) steal_at_start_ = steal;
            const double stolen = steal && steal_at_start_ ? *steal - *steal_at_start_ : -1.0;  // -1: cannot be read
            if (!r_.samples.empty()) {
                const SoakSample& before = r_.samples.back();
                if (!(stolen >= 0 && before.host_steal_s >= 0 && stolen > before.host_steal_s)) {
                    steal_free_.merge(h.since(at_last_sample_));
                    r_.steal_free_s += t - before.t_s;
                }
            }
            at_last_sample_ = h;
            r_.samples.push_back({t, resident_mib(), r_.frames, h.missed_deadlines, stolen});
            next_sample_ = std::floor(t) + 1.0;
            if (o_.progress && (t >= next_progress_ || end)) {
                o_.progress({t, o_.seconds, r_.frames, r_.samples.back().rss_mib, r_.samples.back().haptic_missed});
                next_progress_ += progress_every_;
            }
        }
        if (end) {
            r_.seconds = t;
            r_.stopped_by_signal = signal;
            // read while the loop runs: the session stops next
            r_.haptic_memory_locked = loop_.memory_locked();
            r_.haptic_cpu = loop_.cpu();
        }
        return end;
    }
    void on_step(runner::StepContext& step) override { step.want_frame(true); }  // every frame read back, as a recorder would
    void on_frame(const runner::FrameContext& frame) override { r_.frames += frame.shown ? 1 : 0; }

private:
    const SoakOptions& o_;
    SoakResult& r_;
    haptics::HapticLoop& loop_;
    haptics::PeriodStats& steal_free_;
    haptics::PeriodStats at_last_sample_;
    std::optional<double> steal_at_start_;  // read with the first sample
    std::chrono::steady_clock::time_point start_;
    double progress_every_, next_sample_ = 0, next_progress_;
};

}  // namespace

DeadlineCheck parse_deadline_check(const std::string& name)
{
    for (DeadlineCheck c : {DeadlineCheck::strict, DeadlineCheck::p99, DeadlineCheck::report})
        if (name == to_string(c)) return c;
    throw std::invalid_argument("deadline check '" + name + "': strict, p99 or report");
}

const char* to_string(DeadlineCheck check)
{
    switch (check) {
    case DeadlineCheck::strict: return "strict";
    case DeadlineCheck::p99: return "p99";
    case DeadlineCheck::report: return "report";
    }
    return "?";
}

double soak_warmup_s(double seconds) { return std::min(kSoakWarmupMaxS, std::max(round_trip_s(), kSoakWarmupFraction * seconds)); }

double resident_mib()
{
    // statm: size resident shared text lib data dt, in pages
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long long size = 0, resident = 0;
    const int got = std::fscanf(f, "%llu %llu", &size, &resident);
    std::fclose(f);
    if (got != 2) return 0;
    return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

MemoryVerdict judge_memory(std::span<const SoakSample> samples, double warmup_s)
{
    MemoryVerdict v;
    if (samples.empty()) return v;
    for (const SoakSample& s : samples) v.max_mib = std::max(v.max_mib, s.rss_mib);
    // from the first sample at or after the warm-up on (the last one if the run was shorter)
    std::size_t first = 0;
    while (first + 1 < samples.size() && samples[first].t_s < warmup_s) ++first;
    const std::span<const SoakSample> after = samples.subspan(first);
    v.samples = int(after.size());
    v.start_mib = after.front().rss_mib;
    v.end_mib = after.back().rss_mib;
    v.growth_mib = v.end_mib - v.start_mib;
    if (after.size() < 2) return v;
    // least squares: slope = cov(t, rss) / var(t)
    double mt = 0, mr = 0;
    for (const SoakSample& s : after) mt += s.t_s, mr += s.rss_mib;
    mt /= double(after.size());
    mr /= double(after.size());
    double ctr = 0, ctt = 0;
    for (const SoakSample& s : after) {
        ctr += (s.t_s - mt) * (s.rss_mib - mr);
        ctt += (s.t_s - mt) * (s.t_s - mt);
    }
    const double slope = ctt > 0 ? ctr / ctt : 0.0;  // [MiB/s]
    v.slope_mib_per_min = 60.0 * slope;
    v.trend_mib = slope * (after.back().t_s - after.front().t_s);
    return v;
}

std::vector<SoakBound> judge_soak(const SoakResult& r, DeadlineCheck deadlines)
{
    SoakBound steal_free =
        bound("haptic_period_p99_steal_free", r.haptic_steal_free_p99_ms, kSoakPeriodP99BoundMs, "ms", deadlines != DeadlineCheck::report);
    if (steal_free.enforced && r.steal_free_s < kSoakMinStealFreeS) {
        // too few seconds to tell: said so, and never read as held
        steal_free.enforced = false;
        steal_free.held = false;
        char note[160];
        std::snprintf(note, sizeof note, "not judged: the host took CPU time in all but %.0f s of the run (at least %.0f s needed)",
                      r.steal_free_s, kSoakMinStealFreeS);
        steal_free.note = note;
    }
    return {bound("rss_growth", r.rss.growth_mib, kSoakGrowthBoundMib, "MiB", true),
            bound("rss_trend", r.rss.trend_mib, kSoakTrendBoundMib, "MiB", true),
            bound("validation_messages", double(r.validation_messages), 0, "", true),
            bound("haptic_period_p99", r.haptic_p99_ms, kSoakPeriodP99BoundMs, "ms", deadlines == DeadlineCheck::strict),
            steal_free,
            bound("haptic_missed_deadlines", double(r.haptic_missed), 0, "", deadlines == DeadlineCheck::strict)};
}

bool SoakResult::passed() const
{
    return std::all_of(bounds.begin(), bounds.end(), [](const SoakBound& b) { return b.held || !b.enforced; });
}

SoakResult run_soak_session(const SoakOptions& o)
{
    if (!(o.seconds > 0) || !std::isfinite(o.seconds)) throw std::invalid_argument("soak length " + std::to_string(o.seconds) + " s: must be finite and > 0");
    SoakResult r;
    r.requested_s = o.seconds;
    r.warmup_s = soak_warmup_s(o.seconds);
    r.deadlines = o.deadlines;
    r.width = o.width;
    r.height = o.height;
    const scene::LegModel leg;  // the session's leg is made the same way
    VolumePair volumes = o.volumes;
    if (!volumes.volume) {
        try {
            volumes = soak_volume(leg, o.stop_requested);
        } catch (const StoppedInSetUp& stopped) {
            // no session was started: nothing ran, nothing is judged but that
            r.stopped_by_signal = stopped.signal;
            r.device = "no device yet";
            r.bounds = judge_soak(r, o.deadlines);
            return r;
        }
    }
    // the soak is the runner's offscreen configuration on the real-time clock, every frame drawn
    // and read back; what makes it a soak is its sampler (SoakSampler)
    runner::RunnerConfig config;
    config.name = "soak";
    config.session.clock = session::Clock::real_time;
    config.session.device = std::make_shared<device::ScriptedDevice>(make_round_trip_trajectory(leg), "the slide script, there and back",
                                                                     device::ScriptedDevice::Playback::loop);
    config.max_dt_s = std::numeric_limits<double>::infinity();  // the session's clock is the wall clock's anyway
    config.output = runner::Output::offscreen;
    config.gpu = o.gpu;
    config.gpu.validation = true;
    config.extent = {o.width, o.height};
    config.volume = volumes.volume;
    config.labels = volumes.labels;
    config.observers = o.observers;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner runner(std::move(config));
        r.session_started = true;
        messages = runner.validation_counter();
        r.device = runner.context()->device_name();
        session::Session& session = runner.session();
        r.haptic_priority = session.haptics_note().empty() ? "SCHED_FIFO, CPUs kept awake" : session.haptics_note();
        haptics::HapticLoop& loop = *session.haptic_loop();
        r.haptic_cpus_awake = loop.cpus_awake();
        r.samples.reserve(std::size_t(o.seconds) + 2);  // no growth of our own during the run

        // the haptic periods of the seconds in which the host took no CPU time go to `steal_free`
        // (SoakSampler); cyclictest runs beside the loop for the run, ended with it
        haptics::PeriodStats steal_free;
        Cyclictest cyclictest(o.seconds);
        loop.restart_window();  // the loop's latest tick over the same spell
        runner.add_observer(std::make_shared<SoakSampler>(o, r, loop, steal_free));
        runner.run();  // ends stopping the session: the device's force to zero before anything else
        const physics::RunnerStats ps = session.physics_stats();
        r.physics_steps = ps.steps;
        r.physics_late_steps = ps.overruns;
        const haptics::PeriodStats h = loop.stats();
        r.haptic_ticks = loop.ticks();
        r.haptic_p50_ms = h.error_quantile_ms(0.5);
        r.haptic_p99_ms = h.error_quantile_ms(0.99);
        r.haptic_max_ms = h.max_error_ms;
        r.haptic_missed = h.missed_deadlines;
        r.haptic_late_max_ms = h.window_max_late_ms;
        r.haptic_worst = h.worst;
        r.page_faults = h.page_faults;
        // then cyclictest, so its spell covers the loop's to the end
        const CyclictestResult floor = cyclictest.finish();
        r.cyclictest_max_ms = floor.max_ms;
        r.cyclictest_note = floor.note;
        r.cyclictest_loop_cpu_max_ms = floor.max_on(loop.cpu());
        for (const CyclictestCpu& c : floor.cpus) r.cyclictest_cpus.emplace_back(c.cpu, c.max_ms);
        r.host_steal_s = r.samples.back().host_steal_s;
        r.haptic_steal_free_periods = steal_free.periods;
        r.haptic_steal_free_p99_ms = steal_free.error_quantile_ms(0.99);
    }
    // read after the device is gone: leaks are reported while it is destroyed
    r.validation_messages = messages->load();
    r.rss = judge_memory(r.samples, r.warmup_s);
    r.bounds = judge_soak(r, o.deadlines);
    return r;
}

namespace {

// the loop's latest tick, taken apart (haptics::WorstTick), [us] rounded to 0.1 us
nlohmann::json worst_tick_json(const haptics::WorstTick& w)
{
    const auto us = [](double v) { return std::round(v * 10.0) / 10.0; };
    nlohmann::json before = nlohmann::json::array();
    for (float v : w.late_before_us) before.push_back(us(v));
    return {{"late_ms", w.late_ms},
            {"tick", w.tick},
            {"loop_s", w.at_s},
            {"monotonic_s", w.monotonic_s},
            {"spell_ms", w.spell_ms},
            {"tick_before_us",
             {{"bookkeeping", us(w.before_us)}, {"device_read", us(w.read_us)}, {"force", us(w.force_us)}, {"device_write", us(w.write_us)},
              {"handoffs", us(w.handoff_us)}, {"after", us(w.after_us)}}},
            {"slept", w.slept},
            {"sleep_late_us", us(w.sleep_late_us)},
            {"spin_us", us(w.spin_us)},
            {"cpu_before", w.cpu_before},
            {"cpu_after", w.cpu_after},
            {"voluntary_switches", w.voluntary_switches},
            {"involuntary_switches", w.involuntary_switches},
            {"ran_ms", w.ran_ms},
            {"late_before_us", before}};
}

nlohmann::json cyclictest_cpus_json(const std::vector<std::pair<int, double>>& cpus)
{
    nlohmann::json j = nlohmann::json::array();
    for (const auto& [cpu, max_ms] : cpus) j.push_back({{"cpu", cpu}, {"max_ms", max_ms}});
    return j;
}

}  // namespace

std::string soak_json(const SoakResult& r)
{
    nlohmann::json bounds = nlohmann::json::array();
    for (const SoakBound& b : r.bounds)
        bounds.push_back({{"name", b.name}, {"value", b.value}, {"limit", b.limit}, {"unit", b.unit}, {"held", b.held}, {"enforced", b.enforced},
                          {"note", b.note}});
    nlohmann::json samples = nlohmann::json::array();
    for (const SoakSample& s : r.samples)
        samples.push_back({std::round(s.t_s * 1000.0) / 1000.0, std::round(s.rss_mib * 1000.0) / 1000.0, s.frames, s.haptic_missed,
                           std::round(s.host_steal_s * 1000.0) / 1000.0});
    const nlohmann::json j = {
        {"command", "soak"},
        {"pass", r.passed()},
        {"seconds", r.seconds},
        {"requested_seconds", r.requested_s},
        {"warmup_s", r.warmup_s},
        {"device", r.device},
        {"frame", {{"width", r.width}, {"height", r.height}}},
        {"frames", r.frames},
        {"frames_per_s", r.seconds > 0 ? double(r.frames) / r.seconds : 0.0},
        {"physics_steps", r.physics_steps},
        {"physics_late_steps", r.physics_late_steps},
        {"haptic_ticks", r.haptic_ticks},
        {"haptic_priority", r.haptic_priority},
        {"haptic_cpus_awake", r.haptic_cpus_awake},
        {"haptic_period_p50_ms", r.haptic_p50_ms},
        {"haptic_period_p99_ms", r.haptic_p99_ms},
        {"haptic_period_max_ms", r.haptic_max_ms},
        {"haptic_missed_deadlines", r.haptic_missed},
        {"haptic_late_max_ms", r.haptic_late_max_ms},
        {"haptic_worst_tick", worst_tick_json(r.haptic_worst)},  // that tick taken apart
        {"page_faults", r.page_faults},  // the haptic loop's thread's, after its start
        {"haptic_memory_locked", r.haptic_memory_locked},
        {"haptic_cpu", r.haptic_cpu},
        // cyclictest beside the loop over the run: its latest wake-up, or null and why
        {"cyclictest_max_ms", r.cyclictest_max_ms ? nlohmann::json(*r.cyclictest_max_ms) : nlohmann::json(nullptr)},
        {"cyclictest_note", r.cyclictest_note},
        // its thread on the loop's CPU, and each CPU's [ms]
        {"cyclictest_loop_cpu_max_ms", r.cyclictest_loop_cpu_max_ms ? nlohmann::json(*r.cyclictest_loop_cpu_max_ms) : nlohmann::json(nullptr)},
        {"cyclictest_cpus", cyclictest_cpus_json(r.cyclictest_cpus)},
        {"host_steal_s", r.host_steal_s},
        {"steal_free_s", r.steal_free_s},
        {"haptic_steal_free_periods", r.haptic_steal_free_periods},
        {"haptic_period_p99_steal_free_ms", r.haptic_steal_free_p99_ms},
        {"validation_messages", r.validation_messages},
        {"rss_start_mib", r.rss.start_mib},
        {"rss_end_mib", r.rss.end_mib},
        {"rss_max_mib", r.rss.max_mib},
        {"rss_growth_mib", r.rss.growth_mib},
        {"rss_trend_mib", r.rss.trend_mib},
        {"rss_slope_mib_per_min", r.rss.slope_mib_per_min},
        {"samples_columns", {"t_s", "rss_mib", "frames", "haptic_missed_deadlines", "host_steal_s"}},
        {"samples", samples},  // one a second; frames, missed deadlines and host steal so far
        {"deadlines", to_string(r.deadlines)},
        {"bounds", bounds},
        // the signal that ended the run early, or null (it ran its `requested_seconds`)
        {"stopped_by_signal", r.stopped_by_signal ? nlohmann::json(StopSignals::name(r.stopped_by_signal)) : nlohmann::json(nullptr)},
        {"session_started", r.session_started},
    };
    return j.dump(2) + "\n";
}

}  // namespace echosim::app

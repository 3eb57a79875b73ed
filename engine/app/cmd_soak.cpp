#include <cstdio>
#include <stdexcept>
#include <string>

#include "app/commands.hpp"
#include "app/gpu_args.hpp"
#include "app/soak.hpp"
#include "app/stop_signals.hpp"
#include "io/partial_file.hpp"

namespace echosim::app {

int run_soak(const SoakArgs& args)
{
    if (!args.json.empty() && !output_path_usable("soak", "--json", args.json)) return kExitBadInput;
    SoakOptions o;
    o.seconds = args.seconds;
    o.gpu = context_options(args.gpu);
    o.width = args.width;
    o.height = args.height;
    o.deadlines = parse_deadline_check(args.deadlines);  // checked by the parser
    o.progress = [](const SoakProgress& p) {
        std::printf("echosim soak: %5.0f / %.0f s, %lld frames, resident %.1f MiB, %lld missed haptic deadlines\n", p.t_s, p.seconds, p.frames,
                    p.rss_mib, p.haptic_missed);
        std::fflush(stdout);
    };
    // Ctrl-C or SIGTERM: the run ends at its next frame, judged as far as it went, its report
    // printed and written; exit 128 + the signal (app/stop_signals.hpp)
    const StopSignals stop;
    o.stop_requested = [&stop] { return stop.requested(); };
    std::printf("echosim soak: %.0f s of a scripted session (warm-up %.1f s), making its volume...\n", o.seconds, soak_warmup_s(o.seconds));
    std::fflush(stdout);
    const SoakResult r = run_soak_session(o);
    if (r.stopped_by_signal && !r.session_started)
        std::printf("echosim soak: stopped by %s after %.1f of %.0f s, while its volume was made (no session was started)\n",
                    StopSignals::name(r.stopped_by_signal), r.seconds, r.requested_s);
    else if (r.stopped_by_signal)
        std::printf("echosim soak: stopped by %s after %.1f of %.0f s (the device's force set to zero, the session stopped)\n",
                    StopSignals::name(r.stopped_by_signal), r.seconds, r.requested_s);

    std::printf("echosim soak: %.1f s on %s (%ux%u): %lld frames (%.1f/s), %lld physics steps (%lld late), %lld haptic ticks (%s)\n",
                r.seconds, r.device.c_str(), r.width, r.height, r.frames, r.seconds > 0 ? double(r.frames) / r.seconds : 0.0,
                r.physics_steps, r.physics_late_steps, r.haptic_ticks, r.haptic_priority.c_str());
    std::printf("echosim soak: resident memory %.1f MiB after the warm-up, %.1f MiB at the end (%+.2f MiB; fitted %+.2f MiB, %+.3f MiB/min), "
                "at most %.1f MiB\n",
                r.rss.start_mib, r.rss.end_mib, r.rss.growth_mib, r.rss.trend_mib, r.rss.slope_mib_per_min, r.rss.max_mib);
    std::printf("echosim soak: haptic period error p50 %.3f ms, p99 %.3f ms, max %.3f ms; %lld missed deadlines; %u validation messages\n",
                r.haptic_p50_ms, r.haptic_p99_ms, r.haptic_max_ms, r.haptic_missed, r.validation_messages);
    std::printf("echosim soak: haptic loop's latest tick %.3f ms after its deadline, %lld page faults after its start (memory %s)\n",
                r.haptic_late_max_ms, r.page_faults, r.haptic_memory_locked ? "locked" : "not locked");
    if (const haptics::WorstTick& w = r.haptic_worst; w.late_ms >= 0) {
        char wait[96];
        if (w.slept)
            std::snprintf(wait, sizeof wait, "its sleep returned %.1f us after the time asked, spin %.1f us", w.sleep_late_us, w.spin_us);
        else
            std::snprintf(wait, sizeof wait, "no sleep (the work ended past the sleep's time), spin %.1f us", w.spin_us);
        std::printf("echosim soak:   that tick (%.3f s into the loop): the one before it took %.1f us (read %.1f, force %.1f, write %.1f, "
                    "hand-offs %.1f, bookkeeping %.1f), then %s; CPU %d -> %d; %ld voluntary, %ld involuntary switches; ran %.3f of %.3f ms\n",
                    w.at_s, w.before_us + w.read_us + w.force_us + w.write_us + w.handoff_us + w.after_us, w.read_us, w.force_us, w.write_us,
                    w.handoff_us, w.before_us + w.after_us, wait, w.cpu_before, w.cpu_after, w.voluntary_switches, w.involuntary_switches,
                    w.ran_ms, w.spell_ms);
    }
    if (r.cyclictest_max_ms) {
        std::printf("echosim soak: cyclictest beside it (the machine's floor, a thread on each CPU): latest wake-up %.3f ms", *r.cyclictest_max_ms);
        if (r.cyclictest_loop_cpu_max_ms) std::printf("; on the loop's CPU %d: %.3f ms", r.haptic_cpu, *r.cyclictest_loop_cpu_max_ms);
        std::printf("\n");
    }
    else
        std::printf("echosim soak: cyclictest beside it: no figure (%s)\n", r.cyclictest_note.c_str());
    if (r.host_steal_s < 0)
        std::printf("echosim soak: host steal cannot be read (/proc/stat): every second counts as free of it\n");
    else
        std::printf("echosim soak: host steal %.2f s (all CPUs) in %.0f of %.0f s; in the other %.0f s, haptic period error p99 %.3f ms\n",
                    r.host_steal_s, r.seconds - r.steal_free_s, r.seconds, r.steal_free_s, r.haptic_steal_free_p99_ms);
    for (const SoakBound& b : r.bounds)
        std::printf("echosim soak:   %-28s %10.3f %-3s <= %g %-3s %s%s\n", b.name.c_str(), b.value, b.unit.c_str(), b.limit, b.unit.c_str(),
                    b.held ? "held" : "NOT HELD", !b.note.empty() ? (" (" + b.note + ")").c_str() : b.enforced ? "" : " (reported only)");
    if (!args.json.empty()) {
        io::write_file<std::runtime_error>(args.json, soak_json(r));  // a failure: main names the file
        std::printf("echosim soak: wrote %s\n", args.json.c_str());
    }
    if (r.stopped_by_signal) {
        std::printf("echosim soak: %s (stopped early: judged over %.1f s)\n", r.passed() ? "bounds held" : "bounds not held", r.seconds);
        return StopSignals::exit_code(r.stopped_by_signal);
    }
    if (r.passed()) {
        std::printf("echosim soak: passed\n");
        return kExitOk;
    }
    bool validation = false;
    for (const SoakBound& b : r.bounds)
        if (b.enforced && !b.held) {
            std::fprintf(stderr, "echosim soak: failed: %s %.3f %s over its bound %g %s\n", b.name.c_str(), b.value, b.unit.c_str(), b.limit,
                         b.unit.c_str());
            validation = validation || b.name == "validation_messages";
        }
    return validation ? kExitValidation : kExitFailure;
}

}  // namespace echosim::app

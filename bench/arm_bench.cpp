// Suite "arm": the force path in real time with the simulated arm standing in for a Touch (device/
// simulated_arm.hpp): the session's physics on its thread, the haptic loop on its own, the arm's
// 1 kHz servo on a third, no rendering. The simulated hand holds the handle 15 mm below the skin; the
// handle settles where the coupling's pull equals the force the loop sends. Rows: the loop's rate
// and period error (as the haptics suite has them), the arm's servo rate, the force felt at the end,
// the press it settled at, and how far the settled handle is from that balance (settle_error_N: the
// coupling's pull less the force the arm applied, which a settled handle holds at 0).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "app/default_scene.hpp"
#include "bench/suites.hpp"
#include "device/simulated_arm.hpp"

namespace echosim::bench {
namespace {

void arm_force_path(benchmark::State& state, double seconds)
{
    for (auto _ : state) {
        device::SimulatedArmOptions ao;
        ao.hand.kind = device::HandScript::Kind::hold;
        ao.hand.hold_mm = Eigen::Vector3d(0, -35, 0);  // 15 mm below the skin (the workspace origin is 20 mm above it)
        auto arm = std::make_shared<device::SimulatedArm>(ao);
        session::SessionOptions o;
        o.clock = session::Clock::real_time;
        o.device = arm;
        app::DefaultScene scene(o);
        haptics::HapticLoop& loop = *scene.session.haptic_loop();
        const auto start = std::chrono::steady_clock::now();
        const std::int64_t ticks0 = loop.ticks(), servo0 = arm->servo_ticks();
        double elapsed = 0;
        while (elapsed < seconds) {
            scene.session.advance(0.016);
            std::this_thread::sleep_for(std::chrono::milliseconds(16));  // a window's frame, without the drawing
            elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        const std::int64_t ticks = loop.ticks() - ticks0, servo = arm->servo_ticks() - servo0;
        const haptics::HapticSample last = loop.latest();
        const Eigen::Vector3d applied = arm->applied_force();
        scene.session.stop();
        const haptics::PeriodStats s = loop.stats();
        const double pull_N = ao.arm.coupling_N_per_mm * (ao.hand.hold_mm.y() - last.device.position.y());
        state.counters["rate_hz"] = double(ticks) / elapsed;
        state.counters["servo_hz"] = double(servo) / elapsed;
        state.counters["period_p99_err_ms"] = s.error_quantile_ms(0.99);
        state.counters["period_max_err_ms"] = s.max_error_ms;
        state.counters["missed_deadlines"] = double(s.missed_deadlines);
        state.counters["seconds"] = elapsed;
        state.counters["force_N"] = applied.y();
        state.counters["press_mm"] = -20.0 - last.device.position.y();
        state.counters["settle_error_N"] = std::abs(pull_N + applied.y());
        if (const std::string note = scene.session.haptics_note(); !note.empty()) state.SetLabel(note);
    }
}

}  // namespace

std::shared_ptr<void> register_arm(const SuiteOptions& options)
{
    const double seconds = std::max(10.0, options.min_time_s);
    benchmark::RegisterBenchmark("arm/force-path/1000Hz/simulated-arm", [seconds](benchmark::State& s) { arm_force_path(s, seconds); })
        ->Iterations(1)
        ->Unit(benchmark::kSecond)
        ->UseRealTime();
    return nullptr;
}

}  // namespace echosim::bench

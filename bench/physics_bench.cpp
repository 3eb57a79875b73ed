// Suite "physics": steps per second and CG iterations per step against node count, with the probe
// pressing 10 mm into the patch centre and sliding slowly across it (so contacts change every
// step). Rows for the implicit integrator with the updated and the constant Jacobian, and for the
// explicit integrator at the largest time step that stays stable (found here by halving), so the
// two can be compared by simulated seconds per wall-clock second; and, from 2500 nodes on, the
// implicit one with the step's sweeps shared by every core (up to 8).
// The exam window (session/session.hpp): the same 2500-node press on windows moved to the adductor
// canal and the popliteal fossa (the rate over the whole exam region: a window anywhere steps the
// same grid), and one real-time row whose window follows a hovering probe back and forth between
// them while the haptic loop ticks: how long a move takes (building the window, while the physics
// steps on; the swap, with the physics thread stopped) and what the haptic loop did meanwhile.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "bench/suites.hpp"
#include "core/assets.hpp"
#include "device/scripted_device.hpp"
#include "physics/simulation.hpp"
#include "scene/leg.hpp"
#include "session/session.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::bench {
namespace {

struct PhysicsFixture {
    scene::LegModel leg;
    tissue::SampleParameters fitted = tissue::read_tissue_model(asset_path("models/thigh.json")).samples;
};

struct Run {
    physics::Simulation sim;
    Pose rest;
};

// the probe at time t of the scripted press: in over 0.1 s, then sliding 20 mm/s across the thigh and
// back, 20 mm each way (a continuous path: a jump back would slam the face 10 mm deep into fresh
// skin, which no hand does and which only the implicit integrator survives)
void place_probe(Run& r, double t)
{
    const double press = 10.0 * std::min(1.0, t / 0.1);
    const double slide = 20.0 * std::max(0.0, t - 0.1);
    const double across = 20.0 - std::abs(std::fmod(slide, 40.0) - 20.0);  // 0 -> 20 -> 0 mm
    Pose face = pressed_along_beam(r.rest, press);
    face.position += float(across) * r.rest.axis_x();
    r.sim.state.probe = contact::probe_at(face);
}

Run make_run(const PhysicsFixture& f, int refine, const physics::PhysicsOptions& o)
{
    return Run{physics::Simulation(physics::compile_model(tissue::build_tissue_model(f.leg, f.fitted, refine), o)),
               f.leg.probe_rest_pose(0.5f, 0.5f)};
}

// the exam window's sites: the FV in the adductor canal, the popliteal vein from behind the knee
scene::LimbCoordinates window_site(const scene::LegModel& leg, bool popliteal)
{
    return popliteal ? scene::LimbCoordinates{leg.limb_t_at_z(-450.0f), 0.785f}
                     : scene::LimbCoordinates{leg.limb_t_at_z(-300.0f), leg.patch().centre_theta()};
}

// The session's tissue on a window at `site` (its columns scaled to the skin there, as the session
// runs it), pressed and slid on as the home rows are.
void window_steps(benchmark::State& state, const PhysicsFixture& f, bool popliteal, physics::PhysicsOptions o)
{
    session::SessionOptions so;
    so.window_centre = window_site(f.leg, popliteal);
    so.physics = o;
    const session::Session s(so);
    Run r{physics::Simulation(physics::compile_model(s.tissue_model(), o)), s.leg().probe_rest_pose(0.5f, 0.5f)};
    double t = 0;
    for (; t < 0.15; t += o.time_step) {
        place_probe(r, t);
        r.sim.step();
    }
    long steps = 0;
    for (auto _ : state) {
        place_probe(r, t);
        r.sim.step();
        t += o.time_step;
        ++steps;
    }
    state.counters["nodes"] = double(r.sim.model->node_count());
    state.counters["steps_per_s"] = benchmark::Counter(double(steps), benchmark::Counter::kIsRate);
    state.counters["contacts"] = r.sim.state.last.contacts;
    state.counters["probe_force_N"] = r.sim.state.last.probe_force_N;
    state.counters["resets"] = r.sim.state.resets;
    state.counters["window_z_mm"] = s.leg().limb_point(s.window().centre).z;
}

// Real time, the window following the probe: a scripted hand carries the probe 10 mm over the skin
// down the thigh's front and back between mid-thigh (z = -150 mm) and the adductor canal (z = -300)
// at 500 mm/s, resting 0.2 s at each end, 10 times each way, while the haptic loop ticks and the
// driver advances at 60 Hz; each arrival moves the window (built on the session's builder thread,
// then swapped). With `travel` false the probe hovers over the home patch's centre
// for as long and nothing moves: the loop's own figures on this machine, under the same load.
void window_moves(benchmark::State& state, const PhysicsFixture& f, bool travel)
{
    constexpr int spells = 20;
    constexpr double rest_s = 0.2, travel_s = 0.3, spell_s = rest_s + travel_s;
    for (auto _ : state) {
        auto hover = [&](double t, const Pose& rest) {
            const Pose p = pressed_along_beam(rest, -10.0);
            return device::TrajectoryRow{t, Eigen::Vector3d(p.position.x, p.position.y, p.position.z),
                                         Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized()};
        };
        std::vector<device::TrajectoryRow> rows;
        const double t0 = 0.3;  // the session settles first
        rows.push_back(hover(0.0, f.leg.probe_rest_pose(0.5f, 0.5f)));
        const float theta = f.leg.patch().centre_theta();
        for (int i = 0; i < spells; ++i) {
            const float z = i % 2 == 1 ? -150.0f : -300.0f;
            const Pose at = travel ? f.leg.limb_rest_pose({f.leg.limb_t_at_z(z), theta}) : f.leg.probe_rest_pose(0.5f, 0.5f);
            rows.push_back(hover(t0 + i * spell_s + travel_s, at));
            rows.push_back(hover(t0 + (i + 1) * spell_s, at));
        }
        session::SessionOptions o;
        o.clock = session::Clock::real_time;
        o.window_follows_probe = true;
        o.device = std::make_shared<device::ScriptedDevice>(device::Trajectory::parse(device::format_trajectory(rows), "hover"), "hover");
        session::Session s(o);
        haptics::HapticLoop& loop = *s.haptic_loop();
        std::this_thread::sleep_for(std::chrono::duration<double>(t0));
        loop.restart_window();
        const std::int64_t ticks0 = loop.ticks();
        const physics::RunnerStats physics0 = s.physics_stats();
        const auto start = std::chrono::steady_clock::now();
        double build_sum = 0, swap_sum = 0, felt_max = 0, elapsed = 0;
        int moves = 0;
        while (elapsed < spells * spell_s) {
            std::this_thread::sleep_for(std::chrono::milliseconds(16));
            s.advance(0.016);
            felt_max = std::max(felt_max, s.view().haptic_force_N);
            if (s.window_moves().moves > moves) {
                moves = s.window_moves().moves;
                build_sum += s.window_moves().last_build_ms;
                swap_sum += s.window_moves().last_swap_ms;
            }
            elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        const std::int64_t ticks = loop.ticks() - ticks0;
        const physics::RunnerStats physics1 = s.physics_stats();
        s.stop();
        const haptics::PeriodStats p = loop.stats();
        const session::Session::WindowMoves& m = s.window_moves();
        state.counters["moves"] = m.moves;
        state.counters["abandoned"] = m.abandoned;
        state.counters["build_ms_mean"] = moves > 0 ? build_sum / moves : 0.0;
        state.counters["build_ms_max"] = m.max_build_ms;
        state.counters["swap_ms_mean"] = moves > 0 ? swap_sum / moves : 0.0;
        state.counters["swap_ms_max"] = m.max_swap_ms;
        state.counters["haptic_rate_hz"] = double(ticks) / elapsed;
        state.counters["haptic_late_max_ms"] = p.window_max_late_ms;
        state.counters["haptic_period_p99_err_ms"] = p.error_quantile_ms(0.99);
        state.counters["haptic_missed_deadlines"] = double(p.missed_deadlines);
        state.counters["haptic_felt_max_N"] = felt_max;
        state.counters["physics_rate_hz"] = double(physics1.steps - physics0.steps) / elapsed;
        state.counters["physics_overruns"] = double(physics1.overruns - physics0.overruns);
        state.SetLabel(s.haptics_note().empty() ? "haptic loop real-time" : "haptic loop: " + s.haptics_note());
    }
}

// Simulates `seconds`; false if the state had to be reset (unstable).
bool stable_for(const PhysicsFixture& f, int refine, physics::PhysicsOptions o, double seconds)
{
    Run r = make_run(f, refine, o);
    for (double t = 0; t < seconds; t += o.time_step) {
        place_probe(r, t);
        r.sim.step();
        if (r.sim.state.resets > 0) return false;
    }
    return true;
}

void physics_steps(benchmark::State& state, const PhysicsFixture& f, int refine, physics::PhysicsOptions o)
{
    if (o.integrator == physics::Integrator::explicit_euler) {
        // the largest power-of-two fraction of a millisecond that survives 0.5 s of the script,
        // halved once more as a margin (the benchmark runs longer than the search)
        o.time_step = 1e-3;
        while (o.time_step > 1e-7 && !stable_for(f, refine, o, 1.0)) o.time_step /= 2;
        o.time_step /= 2;
    }
    Run r = make_run(f, refine, o);
    double t = 0;
    for (; t < 0.15; t += o.time_step) {  // warm-up: the probe is in and contacts are established
        place_probe(r, t);
        r.sim.step();
    }
    const physics::TissueState& s = r.sim.state;
    long cg = 0, steps = 0;
    for (auto _ : state) {
        place_probe(r, t);
        r.sim.step();
        t += o.time_step;
        cg += s.last.cg_iterations;
        ++steps;
    }
    state.counters["nodes"] = double(r.sim.model->node_count());
    state.counters["steps_per_s"] = benchmark::Counter(double(steps), benchmark::Counter::kIsRate);
    state.counters["cg_iterations"] = steps ? double(cg) / double(steps) : 0.0;
    state.counters["time_step_s"] = o.time_step;
    state.counters["realtime_factor"] = benchmark::Counter(double(steps) * o.time_step, benchmark::Counter::kIsRate);
    state.counters["contacts"] = s.last.contacts;
    state.counters["probe_force_N"] = s.last.probe_force_N;
    state.counters["resets"] = s.resets;
    state.counters["threads"] = o.threads;
    const bool implicit = o.integrator == physics::Integrator::implicit_euler;
    state.SetLabel(std::string("integrator=") + (implicit ? "implicit" : "explicit") +
                   " jacobian=" + (!implicit ? "none" : o.jacobian == physics::JacobianMode::constant ? "constant" : "updated"));
}

}  // namespace

std::shared_ptr<void> register_physics(const SuiteOptions& options)
{
    auto fixture = std::make_shared<PhysicsFixture>();
    auto add = [&](int refine, physics::Integrator integrator, physics::JacobianMode jacobian, int threads = 1) {
        physics::PhysicsOptions o;
        o.integrator = integrator;
        o.jacobian = jacobian;
        o.threads = threads;
        const int nodes = (7 * refine + 1) * (7 * refine + 1);
        std::string name = "physics/" + std::to_string(nodes) + "/";
        name += integrator == physics::Integrator::implicit_euler ? "implicit" : "explicit";
        if (integrator == physics::Integrator::implicit_euler) name += jacobian == physics::JacobianMode::constant ? "/constant" : "/updated";
        if (threads > 1) name += "/" + std::to_string(threads) + "threads";
        benchmark::RegisterBenchmark(name.c_str(), [f = fixture.get(), refine, o](benchmark::State& s) { physics_steps(s, *f, refine, o); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(options.min_time_s);
    };
    // 64, 484, 2500, 11236 and 50625 nodes: the grid is (7 r + 1)^2
    // with every core on the larger patches, where a step is long enough to share
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    for (int refine : {1, 3, 7, 15, 32}) {
        add(refine, physics::Integrator::implicit_euler, physics::JacobianMode::updated);
        add(refine, physics::Integrator::implicit_euler, physics::JacobianMode::constant);
        if (refine <= 7) add(refine, physics::Integrator::explicit_euler, physics::JacobianMode::updated);
        if (refine >= 7 && cores > 1) add(refine, physics::Integrator::implicit_euler, physics::JacobianMode::updated, std::min(cores, 8));
    }
    for (const bool popliteal : {false, true})
        benchmark::RegisterBenchmark(popliteal ? "physics/2500/implicit/updated/window-popliteal" : "physics/2500/implicit/updated/window-canal",
                                     [f = fixture.get(), popliteal](benchmark::State& s) { window_steps(s, *f, popliteal, physics::PhysicsOptions{}); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(options.min_time_s);
    for (const bool travel : {true, false})
        benchmark::RegisterBenchmark(travel ? "physics/window-move/realtime" : "physics/window-move/realtime/held",
                                     [f = fixture.get(), travel](benchmark::State& s) { window_moves(s, *f, travel); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
    return fixture;
}

}  // namespace echosim::bench

// Suite "physics": steps per second and CG iterations per step against node count, with the probe
// pressing 10 mm into the patch centre and sliding slowly across it (so contacts change every
// step). Rows for the implicit integrator with the updated and the constant Jacobian, and for the
// explicit integrator at the largest time step that stays stable (found here by halving), so the
// two can be compared by simulated seconds per wall-clock second; and, from 2500 nodes on, the
// implicit one with the step's sweeps shared by every core (up to 8).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "bench/suites.hpp"
#include "core/assets.hpp"
#include "physics/simulation.hpp"
#include "scene/leg.hpp"
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
    return fixture;
}

}  // namespace echosim::bench

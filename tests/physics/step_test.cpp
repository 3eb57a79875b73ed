#include "physics/step.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <random>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>

#include "fit/interaction.hpp"
#include "physics/forces.hpp"
#include "physics/physics_fixture.hpp"
#include "physics/simulation.hpp"
#include "counting_new.hpp"

namespace echosim::physics {
namespace {

PhysicsOptions quiet_options()
{
    PhysicsOptions o;
    o.gravity.setZero();
    return o;
}

Eigen::Vector3d normal_of(const tissue::TissueModel& m, std::size_t i) { return {m.normals[i].x, m.normals[i].y, m.normals[i].z}; }
Eigen::Vector3d rest_of(const tissue::TissueModel& m, std::size_t i) { return {m.positions[i].x, m.positions[i].y, m.positions[i].z}; }

// The fitting's interaction model (fit/interaction.cpp) for the indenter at `point` pushed `depth`.
double interaction_model_force(const tissue::TissueModel& m, int point, double depth)
{
    fit::MeasurementSet set;
    for (int p = 0; p < tissue::SampleGrid::count; ++p) {
        const auto k = m.sample_node(p);
        set.samples.push_back({p, fit::ProbeKind::indenter, m.positions[k], m.normals[k], p == point ? depth : 1.0, 0.0});
    }
    const auto prepared = fit::prepare_interaction(fit::sample_mesh(set), set);
    auto ab = [&](int node, int which) { return which == 0 ? m.samples.a[std::size_t(node)] : m.samples.b[std::size_t(node)]; };
    double f = 0;
    EXPECT_TRUE(fit::interaction_force(prepared[std::size_t(point)], ab, m.lambda, f));
    return f;
}

// The probe at its rest pose over the patch, pushed `press` mm in along its axis.
void place_probe(TissueState& s, const Pose& rest, double press)
{
    s.probe = contact::probe_at(pressed_along_beam(rest, press));
}

TEST(Physics, StaticEquilibriumUnderAKnownLoadMatchesTheInteractionModel)
{
    // the fitting's assumption: the loaded node moves, all others stay; a known 6 N pushes node 27.
    // The model itself holds every other node (its boundary), so the solver's filter, the right-hand
    // side and the integration all see the same fixed nodes.
    tissue::TissueModel m = test::shipped_model(1);
    const int point = 27;
    const auto k = m.sample_node(point);
    std::fill(m.boundary.begin(), m.boundary.end(), std::uint8_t(1));
    m.boundary[k] = 0;
    Simulation sim(compile_model(m, quiet_options()));
    TissueState& s = sim.state;
    for (std::size_t i = 0; i < m.node_count(); ++i) ASSERT_EQ(sim.model->fixed(i), i != k) << "node " << i;
    const double load = 6.0;
    s.external.segment<3>(3 * Eigen::Index(k)) = -load * normal_of(m, k);
    for (int i = 0; i < 4000; ++i) sim.step();
    EXPECT_LT(s.v.norm(), 1e-6);  // at rest
    for (std::size_t i = 0; i < m.node_count(); ++i) {
        if (i == k) continue;
        ASSERT_EQ(s.x.segment<3>(3 * Eigen::Index(i)), rest_of(m, i)) << "fixed node " << i << " moved";
    }
    const double depth = (rest_of(m, k) - s.x.segment<3>(3 * Eigen::Index(k))).dot(normal_of(m, k));
    EXPECT_GT(depth, 1.0);
    EXPECT_NEAR(interaction_model_force(m, point, depth), load, 0.01 * load) << "depth " << depth << " mm";
    EXPECT_EQ(s.resets, 0);
}

TEST(Physics, EnergyDecaysWithoutExternalForce)
{
    Simulation sim(compile_model(test::shipped_model(2), quiet_options()));
    const CompiledModel& m = *sim.model;
    TissueState& s = sim.state;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (std::size_t i = 0; i < m.node_count(); ++i)
        if (!m.fixed(i)) s.x.segment<3>(3 * Eigen::Index(i)) += Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double initial = potential_energy(m, s);
    ASSERT_GT(initial, 0.0);
    double previous = initial;
    for (int i = 0; i < 3000; ++i) {
        sim.step();
        const double e = potential_energy(m, s) + kinetic_energy(m, s);
        ASSERT_LE(e, previous * (1 + 1e-9) + 1e-12) << "energy grew at step " << i;
        previous = e;
    }
    EXPECT_LT(previous, 0.01 * initial);
}

TEST(Physics, ExplicitEulerDivergesWhereImplicitStaysStable)
{
    // a finer mesh with the probe pressing 8 mm: the contact penalty makes the system stiff
    const tissue::TissueModel m = test::shipped_model(4);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    auto run = [&](Integrator integrator) {
        PhysicsOptions o;
        o.time_step = 1e-3;
        o.integrator = integrator;
        Simulation sim(compile_model(m, o));
        for (int i = 0; i < 300; ++i) {
            place_probe(sim.state, rest, 8.0 * std::min(1.0, (i + 1) / 100.0));  // press in over 0.1 s, then hold
            sim.step();
        }
        return sim;
    };
    const Simulation implicit = run(Integrator::implicit_euler);
    const Simulation explicit_ = run(Integrator::explicit_euler);
    EXPECT_EQ(implicit.state.resets, 0);
    EXPECT_GT(implicit.state.last.probe_force_N, 1.0);
    EXPECT_LT(implicit.state.last.probe_force_N, 100.0);
    EXPECT_GT(explicit_.state.resets, 0) << "explicit Euler should blow up at 1 ms on this mesh";
}

TEST(Physics, SkinSettlesUnderAStillProbe)
{
    // pressed 10 mm and held: the contact forces derive from an energy and are damped, so the
    // skin comes to rest and the force on the probe is steady (no chatter against the face)
    PhysicsOptions o;
    o.gravity.setZero();
    Simulation sim(compile_model(test::shipped_model(7), o));
    TissueState& s = sim.state;
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    double lo = 1e9, hi = 0;
    for (int i = 0; i < 400; ++i) {
        place_probe(s, rest, 10.0 * std::min(1.0, (i + 1) / 100.0));
        sim.step();
        if (i >= 300) lo = std::min(lo, s.last.probe_force_N), hi = std::max(hi, s.last.probe_force_N);
    }
    EXPECT_GT(lo, 2.0);
    EXPECT_LT(hi - lo, 0.01 * hi);
    EXPECT_LT(kinetic_energy(*sim.model, s), 1e-6);
    EXPECT_EQ(s.resets, 0);
}

TEST(Physics, TissueSettledUnderAStillProbeSleepsAndWakesWhenTheProbeOrTheLoadMoves)
{
    const tissue::TissueModel m = test::shipped_model(7);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    auto press_and_hold = [&](double sleep_after, int steps) {
        PhysicsOptions o;
        o.sleep_after = sleep_after;
        auto sim = std::make_unique<Simulation>(compile_model(m, o));
        for (int i = 0; i < steps; ++i) {
            place_probe(sim->state, rest, 8.0 * std::min(1.0, (i + 1) / 100.0));
            sim->step();
        }
        return sim;
    };
    // never sleeping, the same press: what the sleeping tissue must agree with
    const auto awake = press_and_hold(0.0, 900);
    EXPECT_FALSE(awake->state.last.asleep);
    const auto sim = press_and_hold(PhysicsOptions{}.sleep_after, 900);
    TissueState& s = sim->state;
    ASSERT_TRUE(s.last.asleep) << "still for " << s.still_for << " s, fastest node " << s.v.cwiseAbs().maxCoeff() << " mm/s";
    EXPECT_GT(s.last.probe_force_N, 2.0);
    EXPECT_NEAR(s.last.probe_force_N, awake->state.last.probe_force_N, 1e-3);
    EXPECT_LT((s.x - awake->state.x).cwiseAbs().maxCoeff(), 1e-3);  // [mm]

    // asleep, a step moves nothing and only advances the clock
    const Eigen::VectorXd x = s.x;
    const double t = s.time;
    const int contacts = s.last.contacts;
    EXPECT_EQ(s.v.norm(), 0.0);
    for (int i = 0; i < 50; ++i) sim->step();
    EXPECT_EQ(s.x, x);
    EXPECT_NEAR(s.time, t + 50 * sim->model->options.time_step, 1e-9);
    EXPECT_EQ(s.last.contacts, contacts);

    // the probe a tenth of a millimetre further in: the very next step is awake and pushes back harder
    const double held = s.last.probe_force_N;
    place_probe(s, rest, 8.1);
    sim->step();
    EXPECT_FALSE(s.last.asleep);
    EXPECT_GT(s.last.probe_force_N, held);
    for (int i = 0; i < 400; ++i) sim->step();
    ASSERT_TRUE(s.last.asleep);
    // a load on one node wakes it as well
    s.external[3 * 1250 + 1] = 0.5;
    sim->step();
    EXPECT_FALSE(s.last.asleep);
    EXPECT_NE(s.x, x);
    EXPECT_EQ(s.resets, 0);
}

// Tissue at rest with nothing touching it sleeps while a lifted probe moves about clear of the
// skin (carried between stations), and wakes at the first touch.
TEST(Physics, UntouchedTissueSleepsWhileALiftedProbeMovesAndWakesAtATouch)
{
    PhysicsOptions o;
    o.gravity.setZero();
    Simulation sim(compile_model(test::shipped_model(7), o));
    TissueState& s = sim.state;
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    for (int i = 0; i < 300; ++i) {
        place_probe(s, rest, -5.0);  // 5 mm above the skin, still
        sim.step();
    }
    ASSERT_TRUE(s.last.asleep);
    const Eigen::VectorXd x = s.x;
    // carried across the patch, 5 mm up: the tissue sleeps on, nothing moves
    for (int i = 0; i < 200; ++i) {
        place_probe(s, test::leg().probe_rest_pose(0.5f + 0.001f * float(i), 0.5f), -5.0);
        sim.step();
        ASSERT_TRUE(s.last.asleep) << "step " << i;
    }
    EXPECT_EQ(s.x, x);
    EXPECT_EQ(s.last.contacts, 0);
    // lowered onto the skin and in: the step that touches is awake and pushes back
    const Pose there = test::leg().probe_rest_pose(0.7f, 0.5f);
    int first_touch = -1;
    for (int i = 0; i < 200 && first_touch < 0; ++i) {
        place_probe(s, there, -5.0 + 0.1 * i);
        sim.step();
        if (s.last.contacts > 0) first_touch = i;
    }
    ASSERT_GE(first_touch, 0);
    EXPECT_FALSE(s.last.asleep);
    EXPECT_GT(s.last.probe_force_N, 0.0);
    EXPECT_EQ(s.resets, 0);
}

TEST(Physics, TwoRunsGiveTheSameResult)
{
    // two states stepped on one shared compiled model
    const auto model = compile_model(test::shipped_model(3), PhysicsOptions{});
    const Pose rest = test::leg().probe_rest_pose(0.4f, 0.6f);
    auto run = [&] {
        Simulation sim(model);
        for (int i = 0; i < 150; ++i) {
            place_probe(sim.state, rest, 0.05 * i);
            sim.step();
        }
        return std::move(sim.state);
    };
    const TissueState a = run(), b = run();
    EXPECT_EQ(a.x, b.x);  // bit for bit
    EXPECT_EQ(a.v, b.v);
}

TEST(Physics, ThreadsShareTheStepWithoutChangingTheDynamics)
{
    // the sweeps split by rows give the same springs and nodes; only the order of the dot
    // products' sums differs, so the answers agree to the solver's tolerance, and a team of a
    // given size repeats itself bit for bit
    const tissue::TissueModel m = test::shipped_model(3);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    auto run = [&](int threads) {
        PhysicsOptions o;
        o.threads = threads;
        Simulation sim(compile_model(m, o));
        for (int i = 0; i < 200; ++i) {
            place_probe(sim.state, rest, 0.05 * std::min(i, 100));
            sim.step();
        }
        return std::move(sim.state);
    };
    const TissueState one = run(1), two = run(2), again = run(2);  // (no more threads than CI's cores)
    EXPECT_EQ(two.x, again.x);
    EXPECT_GT(one.last.probe_force_N, 1.0);
    EXPECT_NEAR(two.last.probe_force_N, one.last.probe_force_N, 1e-3 * one.last.probe_force_N);
    EXPECT_LT((two.x - one.x).cwiseAbs().maxCoeff(), 1e-3);  // [mm], the probe 5 mm in
    EXPECT_EQ(two.resets, 0);
}

TEST(Physics, StepAllocatesNothing)
{
    const tissue::TissueModel m = test::shipped_model(3);
    for (int threads : {1, 2}) {
        PhysicsOptions o;
        o.threads = threads;
        Simulation sim(compile_model(m, o));
        place_probe(sim.state, test::leg().probe_rest_pose(0.5f, 0.5f), 5.0);
        sim.step();  // first contact sizes nothing new either, but keep it out of the count
        const long before = test::allocations();
        for (int i = 0; i < 50; ++i) step(*sim.model, sim.state, *sim.team);
        EXPECT_EQ(test::allocations() - before, 0) << threads << " thread(s)";
        EXPECT_GT(sim.state.last.contacts, 0);
    }
}

TEST(Physics, AStepRefusesATeamOrAStateThatIsNotItsModels)
{
    const auto model = compile_model(test::shipped_model(1), PhysicsOptions{});
    TissueState s = make_state(*model);
    ForkJoin two(2);
    EXPECT_THROW(step(*model, s, two), std::invalid_argument);
    const auto finer = compile_model(test::shipped_model(2), PhysicsOptions{});
    ForkJoin one(1);
    EXPECT_THROW(step(*finer, s, one), std::invalid_argument);
    EXPECT_EQ(s.steps, 0);  // refused before anything was touched
    EXPECT_EQ(s.x, model->rest);
    step(*model, s, one);
    EXPECT_EQ(s.steps, 1);
}

TEST(Physics, NanIsDetectedResetAndCounted)
{
    Simulation sim(compile_model(test::shipped_model(1), PhysicsOptions{}));
    TissueState& s = sim.state;
    s.external[3 * 27] = std::nan("");
    sim.step();
    EXPECT_EQ(s.resets, 1);
    EXPECT_TRUE(s.x.allFinite());
    s.external.setZero();
    sim.step();
    EXPECT_EQ(s.resets, 1);
}

}  // namespace
}  // namespace echosim::physics

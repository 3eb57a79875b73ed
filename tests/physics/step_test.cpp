#include "physics/step.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>

#include <gtest/gtest.h>

#include "fit/interaction.hpp"
#include "physics/forces.hpp"
#include "physics/physics_fixture.hpp"

// Every allocation in this test binary is counted, so a test can assert that a step makes none.
namespace {
std::atomic<long> g_allocations{0};
}
void* operator new(std::size_t n)
{
    ++g_allocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

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
    s.probe.active = true;
    s.probe.orientation = Eigen::Quaterniond(rest.orientation.w, rest.orientation.x, rest.orientation.y, rest.orientation.z);
    s.probe.position =
        Eigen::Vector3d(rest.position.x, rest.position.y, rest.position.z) + press * (s.probe.orientation * Eigen::Vector3d::UnitY());
}

TEST(Physics, StaticEquilibriumUnderAKnownLoadMatchesTheInteractionModel)
{
    // the fitting's assumption: the loaded node moves, all others stay; a known 6 N pushes node 27
    const tissue::TissueModel m = test::shipped_model(1);
    const PhysicsOptions o = quiet_options();
    const Scene scene = make_scene(m);
    TissueState s = make_state(m, o, scene);
    const int point = 27;
    const auto k = m.sample_node(point);
    std::fill(s.fixed.begin(), s.fixed.end(), 1);
    s.fixed[k] = 0;
    const double load = 6.0;
    s.external.segment<3>(3 * Eigen::Index(k)) = -load * normal_of(m, k);
    for (int i = 0; i < 4000; ++i) step(m, o, scene, s);
    EXPECT_LT(s.v.norm(), 1e-6);  // at rest
    const double depth = (rest_of(m, k) - s.x.segment<3>(3 * Eigen::Index(k))).dot(normal_of(m, k));
    EXPECT_GT(depth, 1.0);
    EXPECT_NEAR(interaction_model_force(m, point, depth), load, 0.01 * load) << "depth " << depth << " mm";
    EXPECT_EQ(s.resets, 0);
}

TEST(Physics, EnergyDecaysWithoutExternalForce)
{
    const tissue::TissueModel m = test::shipped_model(2);
    const PhysicsOptions o = quiet_options();
    const Scene scene = make_scene(m);
    TissueState s = make_state(m, o, scene);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (std::size_t i = 0; i < m.node_count(); ++i)
        if (!s.fixed[i]) s.x.segment<3>(3 * Eigen::Index(i)) += Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double initial = potential_energy(m, s);
    ASSERT_GT(initial, 0.0);
    double previous = initial;
    for (int i = 0; i < 3000; ++i) {
        step(m, o, scene, s);
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
    const Scene scene = make_scene(m);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    auto run = [&](Integrator integrator) {
        PhysicsOptions o;
        o.time_step = 1e-3;
        o.integrator = integrator;
        TissueState s = make_state(m, o, scene);
        for (int i = 0; i < 300; ++i) {
            place_probe(s, rest, 8.0 * std::min(1.0, (i + 1) / 100.0));  // press in over 0.1 s, then hold
            step(m, o, scene, s);
        }
        return s;
    };
    const TissueState implicit = run(Integrator::implicit_euler);
    const TissueState explicit_ = run(Integrator::explicit_euler);
    EXPECT_EQ(implicit.resets, 0);
    EXPECT_GT(implicit.last.probe_force_N, 1.0);
    EXPECT_LT(implicit.last.probe_force_N, 100.0);
    EXPECT_GT(explicit_.resets, 0) << "explicit Euler should blow up at 1 ms on this mesh";
}

TEST(Physics, SkinSettlesUnderAStillProbe)
{
    // pressed 10 mm and held: the contact forces derive from an energy and are damped, so the
    // skin comes to rest and the force on the probe is steady (no chatter against the face)
    const tissue::TissueModel m = test::shipped_model(7);
    const Scene scene = make_scene(m);
    PhysicsOptions o;
    o.gravity.setZero();
    TissueState s = make_state(m, o, scene);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    double lo = 1e9, hi = 0;
    for (int i = 0; i < 400; ++i) {
        place_probe(s, rest, 10.0 * std::min(1.0, (i + 1) / 100.0));
        step(m, o, scene, s);
        if (i >= 300) lo = std::min(lo, s.last.probe_force_N), hi = std::max(hi, s.last.probe_force_N);
    }
    EXPECT_GT(lo, 2.0);
    EXPECT_LT(hi - lo, 0.01 * hi);
    EXPECT_LT(kinetic_energy(m, s), 1e-6);
    EXPECT_EQ(s.resets, 0);
}

TEST(Physics, TwoRunsGiveTheSameResult)
{
    const tissue::TissueModel m = test::shipped_model(3);
    const Scene scene = make_scene(m);
    const PhysicsOptions o;
    const Pose rest = test::leg().probe_rest_pose(0.4f, 0.6f);
    auto run = [&] {
        TissueState s = make_state(m, o, scene);
        for (int i = 0; i < 150; ++i) {
            place_probe(s, rest, 0.05 * i);
            step(m, o, scene, s);
        }
        return s;
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
    const Scene scene = make_scene(m);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    auto run = [&](int threads) {
        PhysicsOptions o;
        o.threads = threads;
        TissueState s = make_state(m, o, scene);
        for (int i = 0; i < 200; ++i) {
            place_probe(s, rest, 0.05 * std::min(i, 100));
            step(m, o, scene, s);
        }
        return s;
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
    const Scene scene = make_scene(m);
    for (int threads : {1, 2}) {
        PhysicsOptions o;
        o.threads = threads;
        TissueState s = make_state(m, o, scene);
        place_probe(s, test::leg().probe_rest_pose(0.5f, 0.5f), 5.0);
        step(m, o, scene, s);  // first contact sizes nothing new either, but keep it out of the count
        const long before = g_allocations.load();
        for (int i = 0; i < 50; ++i) step(m, o, scene, s);
        EXPECT_EQ(g_allocations.load() - before, 0) << threads << " thread(s)";
        EXPECT_GT(s.last.contacts, 0);
    }
}

TEST(Physics, NanIsDetectedResetAndCounted)
{
    const tissue::TissueModel m = test::shipped_model(1);
    const Scene scene = make_scene(m);
    const PhysicsOptions o;
    TissueState s = make_state(m, o, scene);
    s.external[3 * 27] = std::nan("");
    step(m, o, scene, s);
    EXPECT_EQ(s.resets, 1);
    EXPECT_TRUE(s.x.allFinite());
    s.external.setZero();
    step(m, o, scene, s);
    EXPECT_EQ(s.resets, 1);
}

}  // namespace
}  // namespace echosim::physics

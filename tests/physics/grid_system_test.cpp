// The solver's stencil form of A = M + h D + h^2 K (physics/grid_system) and the force stage's K v,
// against the matrix assembled densely, in double, from the model's own spring list and the
// formulas of the paper's springs, the tissue column and the penalty contact; and conjugate
// gradient's answer against that matrix.
#include "physics/grid_system.hpp"

#include <random>
#include <stdexcept>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "physics/cg.hpp"
#include "physics/forces.hpp"
#include "physics/physics_fixture.hpp"
#include "physics/step.hpp"
#include "tissue/nonlinear_spring.hpp"

namespace echosim::physics {
namespace {

Eigen::Vector3d node(const Eigen::VectorXd& v, std::size_t i) { return v.segment<3>(3 * Eigen::Index(i)); }

// A state of a 15 x 15 patch deformed at random and pressed by the probe, its forces, contacts and
// linearisation evaluated as a step would.
struct Deformed {
    tissue::TissueModel model = test::shipped_model(2);
    Scene scene = make_scene(model);
    PhysicsOptions options;
    TissueState state;

    explicit Deformed(int threads)
    {
        options.threads = threads;
        state = make_state(model, options, scene);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> jitter(-0.3, 0.3), speed(-20.0, 20.0);
        for (Eigen::Index k = 0; k < state.x.size(); ++k) {
            state.x[k] += jitter(rng);
            state.v[k] = speed(rng);
        }
        const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
        state.probe.active = true;
        state.probe.orientation = Eigen::Quaterniond(rest.orientation.w, rest.orientation.x, rest.orientation.y, rest.orientation.z);
        state.probe.position =
            Eigen::Vector3d(rest.position.x, rest.position.y, rest.position.z) + 4.0 * (state.probe.orientation * Eigen::Vector3d::UnitY());
        accumulate_forces(model, options, state, true);
        contact::collide(scene.probe, scene.penalty, state.probe, scene.surface, state.x, state.v, state.contacts, state.force);
    }
};

// K (sk = 1, sd = 0) or A = M + h D + h^2 K (sm = 1, sd = h, sk = h^2), with the contacts' K and D,
// straight from the definitions, fixed nodes not filtered.
Eigen::MatrixXd assemble(const Deformed& d, double sm, double sd, double sk)
{
    const tissue::TissueModel& m = d.model;
    const TissueState& s = d.state;
    const Eigen::Index n = Eigen::Index(m.node_count());
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    auto add = [&](std::size_t i, std::size_t j, const Eigen::Matrix3d& b) { a.block<3, 3>(3 * Eigen::Index(i), 3 * Eigen::Index(j)) += b; };
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    for (const tissue::Spring& sp : m.springs) {
        const Eigen::Vector3d delta = node(s.x, sp.j) - node(s.x, sp.i);
        const double len = delta.norm(), beta = std::max(0.0, 1.0 - sp.rest_length / len);
        const Eigen::Vector3d e = delta / len;
        const Eigen::Matrix3d b = sk * m.lambda * (beta * I + (1.0 - beta) * e * e.transpose()) + sd * m.mu * e * e.transpose();
        add(sp.i, sp.i, b);
        add(sp.j, sp.j, b);
        add(sp.i, sp.j, -b);
        add(sp.j, sp.i, -b);
    }
    for (std::size_t i = 0; i < m.node_count(); ++i) {
        const Eigen::Vector3d nn = Eigen::Vector3d(m.normals[i].x, m.normals[i].y, m.normals[i].z).normalized();
        const double c = -nn.dot(node(s.x, i) - node(s.rest, i));
        EXPECT_LT(c, kMaxCompressionFraction * tissue::spring_limit(m.a[i], m.b[i]));
        const double k = tissue::spring_stiffness(c, m.a[i], m.b[i]);
        const double mass = m.mass[i] * 1e-3;
        const double k_t = d.options.lateral_stiffness_ratio / m.b[i];
        const double damp = 2.0 * d.options.normal_damping_ratio * std::sqrt(mass / m.b[i]);
        const double damp_t = 2.0 * d.options.normal_damping_ratio * std::sqrt(mass * k_t);
        const Eigen::Matrix3d nnt = nn * nn.transpose();
        add(i, i, sm * mass * I + sk * (k * nnt + k_t * (I - nnt)) + sd * (damp * nnt + damp_t * (I - nnt)));
    }
    const Eigen::Vector3d axis = s.contacts.axis;
    for (const contact::Contact& c : s.contacts.contacts)
        for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q)
                add(c.nodes[std::size_t(p)], c.nodes[std::size_t(q)],
                    (sk + sd * d.scene.penalty.damping_time) * c.stiffness * c.weights[p] * c.weights[q] * axis * axis.transpose());
    return a;
}

std::vector<float> planes_of(const Eigen::VectorXd& v)
{
    std::vector<float> p(std::size_t(v.size()));
    to_planes(v.data(), std::size_t(v.size() / 3), p.data());
    return p;
}

Eigen::VectorXd interleaved_of(const std::vector<float>& p)
{
    Eigen::VectorXd v = Eigen::VectorXd::Zero(Eigen::Index(p.size()));
    add_planes_to(p.data(), p.size() / 3, v.data());
    return v;
}

// the stages shared by one thread and by three (15 rows: parts of five)
class GridSystemThreads : public ::testing::TestWithParam<int> {};

TEST_P(GridSystemThreads, ProductMatchesTheAssembledMatrix)
{
    Deformed d(GetParam());
    ASSERT_GT(d.state.contacts.contacts.size(), 10u);
    const double h = d.options.time_step;
    prepare_system(d.model, d.scene.penalty, d.state, h, d.state.system, *d.state.team);
    const Eigen::MatrixXd a = assemble(d, 1.0, h, h * h);

    std::mt19937 rng(3);
    std::normal_distribution<double> gauss;
    Eigen::VectorXd p(a.rows());
    for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = d.state.fixed[std::size_t(k / 3)] ? 0.0 : gauss(rng);
    std::vector<float> out(std::size_t(p.size()));
    const std::vector<float> pp = planes_of(p);
    const double pap = system_product(d.state.grid, d.state.system, pp.data(), out.data(), d.state.cg.rows, *d.state.team);

    Eigen::VectorXd expected = a * p;
    for (std::size_t i = 0; i < d.state.fixed.size(); ++i)
        if (d.state.fixed[i]) expected.segment<3>(3 * Eigen::Index(i)).setZero();  // identity on zero
    const Eigen::VectorXd got = interleaved_of(out);
    EXPECT_LT((got - expected).norm(), 1e-5 * expected.norm());
    EXPECT_NEAR(pap, p.dot(expected), 1e-5 * std::abs(p.dot(expected)));
}

TEST_P(GridSystemThreads, ForceStageStiffnessTimesVelocityMatchesTheAssembledMatrix)
{
    Deformed d(GetParam());
    // the force stage's K v leaves out the contacts (the step adds them from contact/)
    Eigen::VectorXd kv = d.state.stiffness_v;
    contact::add_contact_product(d.state.contacts, d.scene.penalty, 0.0, 1.0, d.state.v, kv);
    const Eigen::VectorXd expected = assemble(d, 0.0, 0.0, 1.0) * d.state.v;
    EXPECT_LT((kv - expected).norm(), 1e-5 * expected.norm());
}

TEST_P(GridSystemThreads, ConjugateGradientSolvesTheAssembledSystem)
{
    Deformed d(GetParam());
    const double h = d.options.time_step;
    prepare_system(d.model, d.scene.penalty, d.state, h, d.state.system, *d.state.team);
    Eigen::MatrixXd a = assemble(d, 1.0, h, h * h);
    for (std::size_t i = 0; i < d.state.fixed.size(); ++i)
        if (d.state.fixed[i]) {
            a.middleRows(3 * Eigen::Index(i), 3).setZero();
            a.middleCols(3 * Eigen::Index(i), 3).setZero();
            a.block<3, 3>(3 * Eigen::Index(i), 3 * Eigen::Index(i)).setIdentity();
        }
    Eigen::VectorXd b = h * d.state.force;
    for (std::size_t i = 0; i < d.state.fixed.size(); ++i)
        if (d.state.fixed[i]) b.segment<3>(3 * Eigen::Index(i)).setZero();

    PhysicsOptions o = d.options;
    o.cg_tolerance = 1e-5;
    d.state.cg.rhs = planes_of(b);
    std::fill(d.state.cg.dv.begin(), d.state.cg.dv.end(), 0.0f);
    const CgResult r = conjugate_gradient(o, d.state.grid, d.state.system, d.state.cg, *d.state.team);
    EXPECT_TRUE(r.finite);
    EXPECT_LT(r.iterations, o.cg_max_iterations);
    const Eigen::VectorXd x = interleaved_of(d.state.cg.dv);
    const Eigen::VectorXd exact = a.ldlt().solve(b);
    // the recurrence's residual in float against the true one in double: within a few times 1e-5
    EXPECT_LT((b - a * x).norm(), 5e-5 * b.norm());
    EXPECT_LT((x - exact).norm(), 1e-3 * exact.norm());
}

INSTANTIATE_TEST_SUITE_P(GridSystem, GridSystemThreads, ::testing::Values(1, 3));

TEST(GridSystem, RejectsSpringsThatAreNotTheGrids)
{
    tissue::TissueModel m = test::shipped_model(1);
    m.springs.push_back({0, 2, 1.0});  // two columns apart
    EXPECT_THROW(make_grid_layout(m), std::invalid_argument);
    m = test::shipped_model(1);
    m.springs.push_back(m.springs.front());  // the same spring twice
    EXPECT_THROW(make_grid_layout(m), std::invalid_argument);
}

}  // namespace
}  // namespace echosim::physics

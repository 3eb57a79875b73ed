// For the tests of the solver's stages: a small patch deformed at random and pressed by the probe,
// with its forces, contacts and linearisation evaluated as a step would; and the implicit step's
// matrix assembled densely, in double, straight from the model's spring list and the formulas of
// the paper's springs, the tissue column and the penalty contact (the independent reference).
#pragma once

#include <random>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "physics/forces.hpp"
#include "physics/grid_layout.hpp"
#include "physics/physics_fixture.hpp"
#include "physics/simulation.hpp"
#include "physics/step.hpp"
#include "tissue/nonlinear_spring.hpp"

namespace echosim::physics::test_support {

inline Eigen::Vector3d node(const Eigen::VectorXd& v, std::size_t i) { return v.segment<3>(3 * Eigen::Index(i)); }

// A 15 x 15 patch. `internal_force` is the force stage's result, before the contacts add theirs.
// `model` and `options` are the definitions the reference is built from; `sim` steps their
// compilation.
struct DeformedPatch {
    tissue::TissueModel model = test::shipped_model(2);
    PhysicsOptions options;
    Simulation sim;
    TissueState& state = sim.state;
    const CompiledModel& compiled = *sim.model;
    ForkJoin& team = *sim.team;
    Eigen::VectorXd internal_force;

    explicit DeformedPatch(int threads) : options(with_threads(threads)), sim(compile_model(model, options))
    {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> jitter(-0.3, 0.3), speed(-20.0, 20.0), push(-0.01, 0.01);
        for (Eigen::Index k = 0; k < state.x.size(); ++k) {
            state.x[k] += jitter(rng);
            state.v[k] = speed(rng);
            state.external[k] = push(rng);
        }
        const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
        state.probe = contact::probe_at(pressed_along_beam(rest, 4.0));
        accumulate_forces(compiled, state, team, true);
        internal_force = state.force;
        contact::collide(compiled.probe, compiled.penalty, state.probe, compiled.surface, state.x, state.v, state.contacts,
                         state.force);
    }

    static PhysicsOptions with_threads(int threads)
    {
        PhysicsOptions o;
        o.threads = threads;
        return o;
    }
};

// The tissue column's parameters at node i, from the model and the options' definitions.
struct Column {
    Eigen::Vector3d n;
    double mass, k_t, damp, damp_t;
};

inline Column column(const DeformedPatch& d, std::size_t i)
{
    const tissue::TissueModel& m = d.model;
    Column c;
    c.n = Eigen::Vector3d(m.normals[i].x, m.normals[i].y, m.normals[i].z).normalized();
    c.mass = m.mass[i] * 1e-3;  // N s^2/mm
    c.k_t = d.options.lateral_stiffness_ratio / m.b[i];
    c.damp = 2.0 * d.options.normal_damping_ratio * std::sqrt(c.mass / m.b[i]);
    c.damp_t = 2.0 * d.options.normal_damping_ratio * std::sqrt(c.mass * c.k_t);
    return c;
}

// K (sk = 1, sd = 0) or A = M + h D + h^2 K (sm = 1, sd = h, sk = h^2), with the contacts' K and D;
// fixed nodes not filtered.
inline Eigen::MatrixXd assemble(const DeformedPatch& d, double sm, double sd, double sk)
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
        const Column c = column(d, i);
        const double compression = -c.n.dot(node(s.x, i) - Eigen::Vector3d(m.positions[i].x, m.positions[i].y, m.positions[i].z));
        EXPECT_LT(compression, kMaxCompressionFraction * tissue::spring_limit(m.a[i], m.b[i]));
        const double k = tissue::spring_stiffness(compression, m.a[i], m.b[i]);
        const Eigen::Matrix3d nnt = c.n * c.n.transpose();
        add(i, i, sm * c.mass * I + sk * (k * nnt + c.k_t * (I - nnt)) + sd * (c.damp * nnt + c.damp_t * (I - nnt)));
    }
    const Eigen::Vector3d axis = s.contacts.axis;
    for (const contact::Contact& c : s.contacts.contacts)
        for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q)
                add(c.nodes[std::size_t(p)], c.nodes[std::size_t(q)],
                    (sk + sd * d.compiled.penalty.damping_time) * c.stiffness * c.weights[p] * c.weights[q] * axis * axis.transpose());
    // across the long sides, each node's own block (contact::add_contact_stiffness_product)
    const Eigen::Vector3d across = s.contacts.across;
    for (const contact::Contact& c : s.contacts.contacts)
        for (int p = 0; p < 3; ++p)
            add(c.nodes[std::size_t(p)], c.nodes[std::size_t(p)], sk * c.across_stiffness * c.weights[p] * c.weights[p] * across * across.transpose());
    return a;
}

inline std::vector<float> planes_of(const Eigen::VectorXd& v)
{
    std::vector<float> p(std::size_t(v.size()));
    to_planes(v.data(), std::size_t(v.size() / 3), p.data());
    return p;
}

inline Eigen::VectorXd interleaved_of(const std::vector<float>& p)
{
    Eigen::VectorXd v = Eigen::VectorXd::Zero(Eigen::Index(p.size()));
    add_planes_to(p.data(), p.size() / 3, v.data());
    return v;
}

}  // namespace echosim::physics::test_support

// The force stage (physics/forces): its forces and its K v against the definitions evaluated
// directly over the model's spring list and nodes (deformed_patch.hpp), with one thread and three.
#include "physics/forces.hpp"

#include <gtest/gtest.h>

#include "physics/deformed_patch.hpp"

namespace echosim::physics {
namespace {

using namespace test_support;

class ForcesThreads : public ::testing::TestWithParam<int> {};

TEST_P(ForcesThreads, ForcesMatchTheModelsDefinitions)
{
    const DeformedPatch d(GetParam());
    const tissue::TissueModel& m = d.model;
    const TissueState& s = d.state;
    Eigen::VectorXd expected = s.external;
    for (const tissue::Spring& sp : m.springs) {  // lambda (L - L0) + mu dL/dt along the spring
        const Eigen::Vector3d delta = node(s.x, sp.j) - node(s.x, sp.i);
        const Eigen::Vector3d e = delta.normalized();
        const Eigen::Vector3d f = (m.lambda * (delta.norm() - sp.rest_length) + m.mu * e.dot(node(s.v, sp.j) - node(s.v, sp.i))) * e;
        expected.segment<3>(3 * Eigen::Index(sp.i)) += f;
        expected.segment<3>(3 * Eigen::Index(sp.j)) -= f;
    }
    for (std::size_t i = 0; i < m.node_count(); ++i) {  // the column, and gravity
        const Column c = column(d, i);
        const Eigen::Vector3d rest(m.positions[i].x, m.positions[i].y, m.positions[i].z);
        const Eigen::Vector3d u = node(s.x, i) - rest, v = node(s.v, i);
        const double compression = -c.n.dot(u);
        const Eigen::Vector3d lateral = u + compression * c.n, lateral_v = v - c.n.dot(v) * c.n;
        expected.segment<3>(3 * Eigen::Index(i)) += (tissue::spring_force(compression, m.a[i], m.b[i]) - c.damp * c.n.dot(v)) * c.n -
                                                    c.k_t * lateral - c.damp_t * lateral_v + c.mass * d.options.gravity;
    }
    const Eigen::VectorXd error = d.internal_force - expected;
    EXPECT_LT(error.norm(), 1e-6 * expected.norm());
    EXPECT_LT(error.cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff());
}

TEST_P(ForcesThreads, StiffnessTimesVelocityMatchesTheAssembledMatrix)
{
    const DeformedPatch d(GetParam());
    // the force stage's K v leaves out the contacts (the step adds them from contact/)
    Eigen::VectorXd kv = d.state.stiffness_v;
    contact::add_contact_stiffness_product(d.state.contacts, d.state.v, kv);
    const Eigen::VectorXd expected = assemble(d, 0.0, 0.0, 1.0) * d.state.v;
    EXPECT_LT((kv - expected).norm(), 1e-5 * expected.norm());
}

INSTANTIATE_TEST_SUITE_P(Forces, ForcesThreads, ::testing::Values(1, 3));

}  // namespace
}  // namespace echosim::physics

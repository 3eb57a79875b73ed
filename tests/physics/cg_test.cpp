// Conjugate gradient (physics/cg) against Eigen's LDLT on the implicit step's matrix assembled
// densely in double (deformed_patch.hpp), with one thread and with three.
#include "physics/cg.hpp"

#include <gtest/gtest.h>

#include "physics/deformed_patch.hpp"

namespace echosim::physics {
namespace {

using namespace test_support;

class CgThreads : public ::testing::TestWithParam<int> {};

TEST_P(CgThreads, SolvesTheAssembledSystem)
{
    DeformedPatch d(GetParam());
    const double h = d.options.time_step;
    prepare_system(d.compiled, d.state, d.state.system, d.team);
    Eigen::MatrixXd a = assemble(d, 1.0, h, h * h);
    for (std::size_t i = 0; i < d.model.node_count(); ++i)
        if (d.model.boundary[i]) {  // Baraff and Witkin's filter: the identity
            a.middleRows(3 * Eigen::Index(i), 3).setZero();
            a.middleCols(3 * Eigen::Index(i), 3).setZero();
            a.block<3, 3>(3 * Eigen::Index(i), 3 * Eigen::Index(i)).setIdentity();
        }
    Eigen::VectorXd b = h * d.state.force;
    for (std::size_t i = 0; i < d.model.node_count(); ++i)
        if (d.model.boundary[i]) b.segment<3>(3 * Eigen::Index(i)).setZero();

    // the same model, solved to a tighter tolerance
    PhysicsOptions o = d.options;
    o.cg_tolerance = 1e-5;
    const auto tight = compile_model(d.model, o);
    d.state.cg.rhs = planes_of(b);
    std::fill(d.state.cg.dv.begin(), d.state.cg.dv.end(), 0.0f);
    const CgResult r = conjugate_gradient(*tight, d.state.system, d.state.cg, d.team);
    EXPECT_TRUE(r.finite);
    EXPECT_LT(r.iterations, o.cg_max_iterations);
    const Eigen::VectorXd x = interleaved_of(d.state.cg.dv);
    const Eigen::VectorXd exact = a.ldlt().solve(b);
    // the recurrence's residual in float against the true one in double: within a few times 1e-5
    EXPECT_LT((b - a * x).norm(), 5e-5 * b.norm());
    EXPECT_LT((x - exact).norm(), 1e-3 * exact.norm());
}

TEST_P(CgThreads, ANanInTheSystemIsReportedNotTakenForConvergence)
{
    DeformedPatch d(GetParam());
    const double h = d.options.time_step;
    prepare_system(d.compiled, d.state, d.state.system, d.team);
    d.state.system.inverse[40] = std::nanf("");  // a free node's preconditioner block
    d.state.cg.rhs = planes_of(h * d.state.force);
    std::fill(d.state.cg.dv.begin(), d.state.cg.dv.end(), 0.0f);
    EXPECT_FALSE(conjugate_gradient(d.compiled, d.state.system, d.state.cg, d.team).finite);
}

INSTANTIATE_TEST_SUITE_P(Cg, CgThreads, ::testing::Values(1, 3));

}  // namespace
}  // namespace echosim::physics

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

// Tissue at rest leaves a right-hand side of round-off: the solve stops at once on the absolute
// floor (PhysicsOptions::cg_absolute_tolerance_N) instead of chasing it to the relative tolerance.
TEST_P(CgThreads, ARoundOffRightHandSideStopsOnTheAbsoluteFloor)
{
    DeformedPatch d(GetParam());
    const double h = d.options.time_step;
    prepare_system(d.compiled, d.state, d.state.system, d.team);
    // a force imbalance of about 1e-9 N over the patch, as a settled patch shows
    Eigen::VectorXd b = h * d.state.force * (1e-9 / d.state.force.norm());
    for (std::size_t i = 0; i < d.model.node_count(); ++i)
        if (d.model.boundary[i]) b.segment<3>(3 * Eigen::Index(i)).setZero();
    const auto solve = [&](double floor_N) {
        PhysicsOptions o = d.options;
        o.cg_absolute_tolerance_N = floor_N;
        const auto model = compile_model(d.model, o);
        d.state.cg.rhs = planes_of(b);
        std::fill(d.state.cg.dv.begin(), d.state.cg.dv.end(), 0.0f);
        return conjugate_gradient(*model, d.state.system, d.state.cg, d.team);
    };
    const CgResult floored = solve(1e-6);
    EXPECT_TRUE(floored.finite);
    EXPECT_EQ(floored.iterations, 0);
    EXPECT_EQ(interleaved_of(d.state.cg.dv).norm(), 0.0);
    // without the floor the same system is solved to the relative tolerance, as any other
    const CgResult relative = solve(0.0);
    EXPECT_GT(relative.iterations, 3);
    EXPECT_LE(relative.relative_residual, d.options.cg_tolerance);
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

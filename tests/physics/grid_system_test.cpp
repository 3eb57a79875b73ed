// The solver's stencil form of A = M + h D + h^2 K (physics/grid_system) against the matrix
// assembled densely, in double, from the model's own spring list (deformed_patch.hpp); shared by
// one thread and by three (15 rows: parts of five).
#include "physics/grid_system.hpp"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "physics/deformed_patch.hpp"

namespace echosim::physics {
namespace {

using namespace test_support;

// zero at the model's fixed nodes
Eigen::VectorXd random_vector(const CompiledModel& model)
{
    std::mt19937 rng(3);
    std::normal_distribution<double> gauss;
    Eigen::VectorXd p(model.rest.size());
    for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = model.fixed(std::size_t(k / 3)) ? 0.0 : gauss(rng);
    return p;
}

class GridSystemThreads : public ::testing::TestWithParam<int> {};

TEST_P(GridSystemThreads, ProductMatchesTheAssembledMatrix)
{
    DeformedPatch d(GetParam());
    ASSERT_GT(d.state.contacts.contacts.size(), 10u);
    const double h = d.options.time_step;
    prepare_system(d.compiled, d.state, d.state.system, d.team);
    const Eigen::MatrixXd a = assemble(d, 1.0, h, h * h);

    const Eigen::VectorXd p = random_vector(d.compiled);
    std::vector<float> out(std::size_t(p.size()));
    const std::vector<float> pp = planes_of(p);
    const double pap = system_product(d.compiled, d.state.system, pp.data(), out.data(), d.state.cg.scratch, d.team);

    Eigen::VectorXd expected = a * p;
    for (std::size_t i = 0; i < d.model.node_count(); ++i)
        if (d.model.boundary[i]) expected.segment<3>(3 * Eigen::Index(i)).setZero();  // identity on zero
    const Eigen::VectorXd got = interleaved_of(out);
    EXPECT_LT((got - expected).norm(), 1e-5 * expected.norm());
    EXPECT_NEAR(pap, p.dot(expected), 1e-5 * std::abs(p.dot(expected)));
}

TEST_P(GridSystemThreads, ProductMatchesOnTheGridsEdgesToo)
{
    // the rim is fixed in the dynamics, which masks its rows; with no node fixed (the same patch,
    // compiled from a model whose boundary is empty), every row of the stencil (first and last
    // rows and columns included) must match the matrix
    DeformedPatch d(GetParam());
    tissue::TissueModel loose = d.model;
    std::fill(loose.boundary.begin(), loose.boundary.end(), std::uint8_t(0));
    const auto unfixed = compile_model(loose, d.options);
    for (std::size_t i = 0; i < d.model.node_count(); ++i) ASSERT_FALSE(unfixed->fixed(i));
    GridSystem system = make_grid_system(unfixed->grid);
    system.contacts.reserve(d.state.contacts.contacts.size());
    const double h = d.options.time_step;
    prepare_system(*unfixed, d.state, system, d.team);
    const Eigen::MatrixXd a = assemble(d, 1.0, h, h * h);

    const Eigen::VectorXd p = random_vector(*unfixed);
    std::vector<float> out(std::size_t(p.size()));
    const std::vector<float> pp = planes_of(p);
    system_product(*unfixed, system, pp.data(), out.data(), d.state.cg.scratch, d.team);
    const Eigen::VectorXd expected = a * p;
    const Eigen::VectorXd error = interleaved_of(out) - expected;
    EXPECT_LT(error.norm(), 1e-5 * expected.norm());
    EXPECT_LT(error.cwiseAbs().maxCoeff(), 1e-5 * expected.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(GridSystem, GridSystemThreads, ::testing::Values(1, 3));

}  // namespace
}  // namespace echosim::physics

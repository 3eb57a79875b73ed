#include "physics/grid_layout.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

#include "physics/physics_fixture.hpp"

namespace echosim::physics {
namespace {

TEST(GridLayout, MapsEverySpringToItsDirectionAndFirstNode)
{
    const tissue::TissueModel m = test::shipped_model(1);  // 8 x 8
    const GridLayout g = make_grid_layout(m);
    ASSERT_EQ(g.spring_first.size(), m.springs.size());
    for (std::size_t k = 0; k < m.springs.size(); ++k) {
        const std::size_t first = g.spring_first[k], second = first + g.offset(g.spring_direction[k]);
        const auto [i, j] = std::minmax(m.springs[k].i, m.springs[k].j);
        EXPECT_EQ(first, i);
        EXPECT_EQ(second, j);
    }
    EXPECT_EQ(g.spring_first.size(), std::size_t(7 * 8 + 8 * 7 + 2 * 7 * 7));  // east, south, both diagonals
}

TEST(GridLayout, RejectsSpringsThatAreNotTheGrids)
{
    tissue::TissueModel m = test::shipped_model(1);
    m.springs.push_back({0, 2, 1.0});  // two columns apart
    EXPECT_THROW(make_grid_layout(m), std::invalid_argument);
    m = test::shipped_model(1);
    m.springs.push_back(m.springs.front());  // the same spring twice
    EXPECT_THROW(make_grid_layout(m), std::invalid_argument);
    m = test::shipped_model(1);
    m.springs.push_back({63, 64, 1.0});  // beyond the last node
    EXPECT_THROW(make_grid_layout(m), std::invalid_argument);
}

TEST(GridLayout, PartsTakeWholeRows)
{
    const GridLayout g = make_grid_layout(test::shipped_model(2));  // 15 x 15
    std::size_t next = 0;
    for (int part = 0; part < 4; ++part) {
        const auto [first, end] = part_nodes(g, part, 4);
        EXPECT_EQ(first, next);
        EXPECT_EQ(first % std::size_t(g.cols), 0u);
        next = end;
    }
    EXPECT_EQ(next, g.n);
}

}  // namespace
}  // namespace echosim::physics

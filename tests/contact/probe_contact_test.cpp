#include "contact/probe_contact.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace echosim::contact {
namespace {

// A flat 2 x 2-node patch (one cell, two triangles) in the plane y = `height`, spanning
// [x0, x0 + size] x [z0, z0 + size].
Eigen::VectorXd flat_patch(double height, double x0, double z0, double size)
{
    Eigen::VectorXd x(12);
    x << x0, height, z0, x0, height, z0 + size, x0 + size, height, z0, x0 + size, height, z0 + size;
    return x;
}

TEST(ProbeContact, FlatSkinPressedEvenlyGivesPressureTimesFaceArea)
{
    // the skin at y = 2, the face at y = 3 looking along +y (identity orientation): every skin
    // point under the 40 x 10 mm face lies 1 mm inside the box
    const Eigen::VectorXd x = flat_patch(2.0, -100, -100, 200);
    const PatchSurface surface = make_patch_surface(2, 2, x, 0.25);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    const PenaltyLaw law;
    ASSERT_GT(collide(ProbeGeometry{}, law, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    // the face's effective area: 40 x 10 mm with the pressure fading linearly over the 1 mm rounded
    // rim: the inner 38 x 8 mm plus the integral over the rim band of d (perimeter 100 - 8 d),
    // 304 + 50 - 8/3 = 351.33 mm^2; sampled at 0.25 mm, within 2 %
    const double effective_area = 304.0 + 50.0 - 8.0 / 3.0;
    EXPECT_NEAR(set.total_force, law.pressure(1.0) * effective_area, 0.02 * law.pressure(1.0) * effective_area);
    // along +y only, and the nodes together carry exactly what the probe feels
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(force[3 * k], 0.0);
        EXPECT_EQ(force[3 * k + 2], 0.0);
        sum += force[3 * k + 1];
    }
    EXPECT_NEAR(sum, set.total_force, 1e-9 * sum);
}

TEST(ProbeContact, BarycentricSplitFollowsWhereTheFacePresses)
{
    // the face pushes the patch off-centre: nodes near it take more of the force, in proportion
    // to the (bilinear) weights of the face's centre in the cell
    const Eigen::VectorXd x = flat_patch(2.0, -30, -20, 100);  // face centre at 30 %, 20 % of the cell
    const PatchSurface surface = make_patch_surface(2, 2, x, 0.25);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    collide(ProbeGeometry{}, PenaltyLaw{}, probe, surface, x, Eigen::VectorXd::Zero(12), set, force);
    const double total = set.total_force;
    // the cell's nodes: 0 (x0, z0), 1 (x0, z0 + s), 2 (x0 + s, z0), 3 (x0 + s, z0 + s); triangles
    // (0, 2, 3) and (0, 3, 1) split it along its diagonal. The face [-20, 20] x [-5, 5] lies at
    // u = x - x0 in [10, 50], w = z - z0 in [15, 25], below the diagonal (u > w) except for a
    // corner, so it is nearly all on triangle (0, 2, 3): weights 1 - u/s, (u - w)/s, w/s.
    const double s = 100, u = 30, w = 20;
    EXPECT_NEAR(force[1] / total, 1 - u / s, 0.02);
    EXPECT_NEAR(force[7] / total, (u - w) / s, 0.02);
    EXPECT_NEAR(force[10] / total, w / s, 0.02);
    EXPECT_NEAR(force[4] / total, 0.0, 0.02);
}

TEST(ProbeContact, NoContactWhenTheSkinIsBeyondTheFaceOrAside)
{
    const Eigen::VectorXd x = flat_patch(5.0, -100, -100, 200);
    const PatchSurface surface = make_patch_surface(2, 2, x, 1.0);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);  // the skin at y = 5 lies beyond the face: no touch
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    EXPECT_EQ(collide(ProbeGeometry{}, PenaltyLaw{}, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    probe.position = Eigen::Vector3d(500, 6, 0);  // pressing, but far to the side
    EXPECT_EQ(collide(ProbeGeometry{}, PenaltyLaw{}, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    EXPECT_EQ(force.norm(), 0.0);
}

TEST(ProbeContact, TiltedProbePushesAlongItsOwnAxis)
{
    // a wall at x = -2; the probe turned 90 degrees about z so its beam (+y) is world -x
    Eigen::VectorXd x(12);
    x << -2, -100, -100, -2, -100, 100, -2, 100, -100, -2, 100, 100;
    const PatchSurface surface = make_patch_surface(2, 2, x, 1.0);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;
    probe.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
    probe.position = Eigen::Vector3d(-3, 0, 0);  // face 1 mm past the wall
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    ASSERT_GT(collide(ProbeGeometry{}, PenaltyLaw{}, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) total += force.segment<3>(3 * k);
    EXPECT_LT(total.x(), 0.0);
    EXPECT_NEAR(total.y(), 0.0, 1e-9);
    EXPECT_NEAR(total.z(), 0.0, 1e-9);
}

TEST(GridBvh, FindsExactlyTheCellsUnderABox)
{
    // a 5 x 5-node flat grid, 10 mm cells; a box over the cells (1..2, 1..2)
    Eigen::VectorXd x(75);
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 5; ++c) x.segment<3>(3 * (r * 5 + c)) = Eigen::Vector3d(10.0 * c, 0, 10.0 * r);
    GridBvh bvh(5, 5);
    bvh.refit(x);
    Aabb box;
    box.grow({12, -1, 12});
    box.grow({28, 1, 28});
    std::vector<std::uint32_t> cells;
    bvh.query(box, x, cells);
    std::sort(cells.begin(), cells.end());
    EXPECT_EQ(cells, (std::vector<std::uint32_t>{5, 6, 9, 10}));  // cell index r * 4 + c
    // after the grid moves away, nothing
    x.array() += 1000.0;
    bvh.refit(x);
    cells.clear();
    bvh.query(box, x, cells);
    EXPECT_TRUE(cells.empty());
}

}  // namespace
}  // namespace echosim::contact

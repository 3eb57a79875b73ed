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

// The axial pressure a flat skin feels at distance e beyond the flat part of the face, towards an
// end of the array, the skin `depth` [mm] inside the face's plane, from the geometry of an end
// rounded with radius r (independent of probe_depth's signed distance): the end is a quarter
// circle whose centre lies r inside the flat part's end and r behind the face's plane; a skin point
// inside it is r - |point - centre| deep, and the circle's normal there leans
// (r - depth) / |point - centre| toward the axis.
double rim_pressure(const PenaltyLaw& law, double r, double depth, double e)
{
    const double from_centre = std::hypot(e, r - depth);
    return from_centre < r ? law.pressure(r - from_centre) * (r - depth) / from_centre : 0.0;
}

TEST(ProbeContact, FlatSkinPressedEvenlyGivesPressureOverTheRoundedFace)
{
    // the skin at y = 2.5, the face at y = 3 looking along +y (identity orientation): the skin
    // under the face's flat 38 x 10 mm lies 0.5 mm inside it, and meets the array's 1 mm rounded
    // ends; across the array the pressure fades over the last 1 mm to the long edges
    const double depth = 0.5, r = ProbeGeometry{}.edge_radius;
    const Eigen::VectorXd x = flat_patch(3.0 - depth, -100, -100, 200);
    const PatchSurface surface = make_patch_surface(2, 2, x, 0.1);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    const PenaltyLaw law;
    ASSERT_GT(collide(ProbeGeometry{}, law, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    // across an end, the pressure over its rounded band by the midpoint rule; along the array, a
    // fade from 1 to 0 over the last r of the thickness weighs a band by r / 2
    const double flat_w = 40.0 - 2 * r, flat_t = 10.0 - 2 * r;
    double band = 0;
    const int steps = 20000;
    for (int i = 0; i < steps; ++i) band += rim_pressure(law, r, depth, (i + 0.5) * r / steps) * r / steps;
    const double across = flat_t + 2 * (r / 2);  // the thickness, weighed by the fade
    const double expected = law.pressure(depth) * flat_w * across + 2 * band * across;
    // sampled at 0.1 mm: within 1 %
    EXPECT_NEAR(set.total_force, expected, 0.01 * expected);
    // (what a sharp-edged face of the same size would feel is more than 9 % more)
    EXPECT_GT(law.pressure(depth) * 400.0, 1.09 * expected);
    // along +y only, and the nodes together carry exactly what the probe feels
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(force[3 * k], 0.0);
        EXPECT_EQ(force[3 * k + 2], 0.0);
        sum += force[3 * k + 1];
    }
    EXPECT_NEAR(sum, set.total_force, 1e-9 * sum);
}

// The probe's profile against points placed by hand: under the face (whatever z: the long edges
// are not rounded), over a rounded end (where the normal leans out by the angle of the point about
// the end's centre), beside an end, outside.
TEST(ProbeContact, ProbeDepthFollowsTheRoundedEnds)
{
    const ProbeGeometry g;  // 40 x 10 mm face, 1 mm rim
    const double hw = 20.0;
    ProbeDepth d = probe_depth(g, {3.0, -0.4, 1.0});
    EXPECT_NEAR(d.penetration, 0.4, 1e-12);
    EXPECT_NEAR(d.normal.y(), 1.0, 1e-12);
    EXPECT_EQ(d.turn, 0.0);
    EXPECT_NEAR(probe_depth(g, {3.0, -0.4, 4.9}).penetration, 0.4, 1e-12);
    // over an end: 0.6 mm from the end's centre (19, -1, z) at 30 degrees from the axis
    const double a = M_PI / 6, from_centre = 0.6;
    d = probe_depth(g, {hw - 1.0 + from_centre * std::sin(a), -1.0 + from_centre * std::cos(a), 0.0});
    EXPECT_NEAR(d.penetration, 0.4, 1e-12);
    EXPECT_NEAR(d.normal.x(), std::sin(a), 1e-12);
    EXPECT_NEAR(d.normal.y(), std::cos(a), 1e-12);
    EXPECT_NEAR(d.turn, 1.0 / from_centre, 1e-12);
    // deep beside the end of the array: pushed out of the side, not along the axis
    d = probe_depth(g, {-hw + 0.3, -8.0, 0.0});
    EXPECT_NEAR(d.penetration, 0.3, 1e-12);
    EXPECT_NEAR(d.normal.x(), -1.0, 1e-12);
    // under the flat of the face but deeper than it is from an end: the end is nearer
    d = probe_depth(g, {-hw + 3.0, -5.0, 0.0});
    EXPECT_NEAR(d.penetration, 3.0, 1e-12);
    EXPECT_NEAR(d.normal.x(), -1.0, 1e-12);
    // outside the rounded end, though inside the box
    d = probe_depth(g, {hw - 0.1, -0.1, 0.0});
    EXPECT_LT(d.penetration, 0.0);
    EXPECT_LT(probe_depth(g, {0.0, 0.5, 0.0}).penetration, 0.0);  // beyond the face
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

// A strip of skin standing in the plane z = 5 - s, s inside the face's long side (z = 5), 10 to
// 12 mm behind the face: skin wrapped up the side of a deeply pressed probe, in the fade.
struct SideStrip {
    double force = 0, across_stiffness = 0;
    Eigen::Vector3d across = Eigen::Vector3d::Zero();
    Eigen::VectorXd stiffness_times_unit_across;  // add_contact_stiffness_product on every node moved 1 mm across
};
SideStrip side_strip(double s)
{
    Eigen::VectorXd x(12);
    const double z = 5.0 - s;
    x << -5, -12, z, -5, -10, z, 5, -12, z, 5, -10, z;
    const PatchSurface surface = make_patch_surface(2, 2, x, 0.05);
    ContactSet set = make_contact_set(surface);
    ProbeState probe;
    probe.active = true;  // face at y = 0 looking along +y, its long sides at z = +-5
    Eigen::VectorXd force = Eigen::VectorXd::Zero(12);
    EXPECT_GT(collide(ProbeGeometry{}, PenaltyLaw{}, probe, surface, x, Eigen::VectorXd::Zero(12), set, force), 0);
    SideStrip strip;
    strip.force = set.total_force;
    strip.across = set.across;
    for (const Contact& c : set.contacts) strip.across_stiffness += c.across_stiffness;
    Eigen::VectorXd unit(12);
    for (int k = 0; k < 4; ++k) unit.segment<3>(3 * k) = Eigen::Vector3d::UnitZ();
    strip.stiffness_times_unit_across = Eigen::VectorXd::Zero(12);
    add_contact_stiffness_product(set, unit, strip.stiffness_times_unit_across);
    return strip;
}

// The fade pushes skin along the axis by where it lies across the long side: the implicit step is
// told how steeply (Contact::across_stiffness), the force's own derivative, measured here by moving
// the strip across; under the face's full width it is told nothing. The skin on a large patient's
// deeply pressed probe chattered without it (bench/RESULTS.md, "The contact's long sides").
TEST(ProbeContact, TheStepIsToldHowTheFadeChangesAcrossTheLongSides)
{
    const double s = 0.5, ds = 0.05;
    const SideStrip at = side_strip(s);
    const double slope = (side_strip(s + ds).force - side_strip(s - ds).force) / (2 * ds);  // linear in the fade: exact
    ASSERT_GT(slope, 0.0);
    EXPECT_NEAR(at.across_stiffness, slope, 1e-6 * slope);
    EXPECT_NEAR(at.across.z(), 1.0, 1e-12);
    // in the product, each node's own share along the across direction: the samples' w^2 sum to
    // less than the strip's whole k (sum over nodes of w^2 < 1), and none of it along the axis
    double along_across = 0;
    for (int k = 0; k < 4; ++k) {
        along_across += at.stiffness_times_unit_across[3 * k + 2];
        EXPECT_EQ(at.stiffness_times_unit_across[3 * k], 0.0);
    }
    EXPECT_GT(along_across, 0.1 * at.across_stiffness);
    EXPECT_LT(along_across, at.across_stiffness);
    // past the fade, under the face's full width: nothing changes across, nothing is told
    EXPECT_EQ(side_strip(1.5).across_stiffness, 0.0);
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

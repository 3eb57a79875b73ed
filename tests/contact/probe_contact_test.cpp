#include "contact/probe_contact.hpp"

#include <gtest/gtest.h>

namespace echosim::contact {
namespace {

TEST(ProbeContact, ForceIsAlongTheAxisAndSplitByBarycentricWeights)
{
    // one large flat triangle in the plane y = 2 (world), the probe's face at y = 3 looking along +y:
    // the skin lies 1 mm in front of the face everywhere under it
    const Eigen::Vector3d centre(0, 2, 0);
    // vertices placed so the face centre has barycentric coordinates (0.2, 0.3, 0.5)
    const Eigen::Vector3d b(200, 2, 0), c(0, 2, 200);
    const Eigen::Vector3d a = (centre - 0.3 * b - 0.5 * c) / 0.2;
    Eigen::VectorXd x(9);
    x << a, b, c;
    const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}};
    ProbeGeometry g;
    PenaltyLaw law;
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);  // identity orientation: probe +y is world +y
    ContactSet set = make_contact_set(3, 1, g);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(9);
    const int n = collide(g, law, probe, triangles, x, set, force);
    EXPECT_EQ(n, 400);  // every sample of the 40 x 10 face, 1 mm apart
    const double expected = law.pressure(1.0) * 400.0;
    EXPECT_NEAR(set.total_force, expected, 1e-9 * expected);
    // along +y only, the face's samples are symmetric about its centre: the mean weights are the centre's
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(force[3 * k], 0.0, 1e-12);
        EXPECT_NEAR(force[3 * k + 2], 0.0, 1e-12);
    }
    EXPECT_NEAR(force[1], 0.2 * expected, 1e-9 * expected);
    EXPECT_NEAR(force[4], 0.3 * expected, 1e-9 * expected);
    EXPECT_NEAR(force[7], 0.5 * expected, 1e-9 * expected);
}

TEST(ProbeContact, NoContactWhenTheSkinIsBehindTheFaceOrOutside)
{
    Eigen::VectorXd x(9);
    x << -100, 5, -100, 100, 5, -100, 0, 5, 100;
    const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}};
    ProbeGeometry g;
    ProbeState probe;
    probe.active = true;
    probe.position = Eigen::Vector3d(0, 3, 0);  // the skin at y = 5 lies beyond the face: no touch
    ContactSet set = make_contact_set(3, 1, g);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(9);
    EXPECT_EQ(collide(g, PenaltyLaw{}, probe, triangles, x, set, force), 0);
    probe.position = Eigen::Vector3d(500, 6, 0);  // pressing, but far to the side
    EXPECT_EQ(collide(g, PenaltyLaw{}, probe, triangles, x, set, force), 0);
    EXPECT_EQ(force.norm(), 0.0);
}

TEST(ProbeContact, TiltedProbePushesAlongItsOwnAxis)
{
    // the probe turned 90 degrees about z: its +y (the beam) is world -x
    Eigen::VectorXd x(9);
    x << -2, -100, -100, -2, 100, -100, -2, 0, 100;  // a wall at x = -2
    const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}};
    ProbeState probe;
    probe.active = true;
    probe.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
    probe.position = Eigen::Vector3d(-3, 0, 0);  // face 1 mm past the wall
    ContactSet set = make_contact_set(3, 1, ProbeGeometry{});
    Eigen::VectorXd force = Eigen::VectorXd::Zero(9);
    ASSERT_GT(collide(ProbeGeometry{}, PenaltyLaw{}, probe, triangles, x, set, force), 0);
    const Eigen::Vector3d total = force.segment<3>(0) + force.segment<3>(3) + force.segment<3>(6);
    EXPECT_LT(total.x(), 0.0);
    EXPECT_NEAR(total.y(), 0.0, 1e-9);
    EXPECT_NEAR(total.z(), 0.0, 1e-9);
}

}  // namespace
}  // namespace echosim::contact

#include "scene/tube.hpp"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim::scene {
namespace {

Tube elliptic_cylinder(float a, float b)
{
    Tube t;
    t.e1 = {1, 0, 0};
    t.e2 = {0, 1, 0};
    for (float z : {0.0f, -100.0f, -200.0f, -300.0f}) t.stations.push_back({{0, 0, z}, a, a, b, b});
    return t;
}

TEST(Tube, PointsLieOnTheAnalyticEllipse)
{
    const Tube t = elliptic_cylinder(80.0f, 50.0f);
    for (float theta = 0.0f; theta < 6.28f; theta += 0.37f) {
        const glm::vec3 p = t.point(1.3f, theta);
        EXPECT_NEAR((p.x / 80.0f) * (p.x / 80.0f) + (p.y / 50.0f) * (p.y / 50.0f), 1.0f, 1e-5f);
        EXPECT_NEAR(p.z, -130.0f, 1e-3f);
        // the point lies on the ray at angle theta
        EXPECT_NEAR(std::atan2(p.y, p.x), std::atan2(std::sin(theta), std::cos(theta)), 1e-4f);
    }
}

TEST(Tube, NormalsAreOutwardAndMatchTheEllipseGradient)
{
    const Tube t = elliptic_cylinder(80.0f, 50.0f);
    for (float theta = 0.1f; theta < 6.28f; theta += 0.5f) {
        const glm::vec3 p = t.point(1.5f, theta);
        const glm::vec3 n = t.outward_normal(1.5f, theta);
        const glm::vec3 gradient = glm::normalize(glm::vec3(p.x / (80.0f * 80.0f), p.y / (50.0f * 50.0f), 0.0f));
        EXPECT_NEAR(glm::dot(n, gradient), 1.0f, 1e-3f);
    }
}

TEST(Tube, StationsAreInterpolatedThroughTheirValues)
{
    Tube t = elliptic_cylinder(80.0f, 50.0f);
    t.stations[2].r_pos1 = 60.0f;
    EXPECT_NEAR(t.at(2.0f).r_pos1, 60.0f, 1e-5f);  // Catmull-Rom passes through its stations
    EXPECT_NEAR(t.at(1.0f).r_pos1, 80.0f, 1e-5f);
    const float mid = t.at(1.5f).r_pos1;
    EXPECT_LT(mid, 80.0f);
    EXPECT_GT(mid, 60.0f);
}

TEST(Tube, MeshSkipsCellsAndCloses)
{
    const Tube t = elliptic_cylinder(80.0f, 50.0f);
    TubeMeshOptions o;
    o.rings_per_span = 2;
    o.segments = 8;
    const Mesh full = build_tube(t, o);
    o.skip_cell = [](int ring, int seg) { return ring == 1 && seg < 2; };
    const Mesh holed = build_tube(t, o);
    EXPECT_EQ(full.indices.size() - holed.indices.size(), 2u * 6u);
    // rings * segments + two pointed caps' centres
    EXPECT_EQ(full.vertices.size(), std::size_t(7 * 8 + 2));
}

}  // namespace
}  // namespace echosim::scene

#include "scene/camera.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim::scene {
namespace {

TEST(OrbitCamera, TargetProjectsToTheCentreAndUpIsAnterior)
{
    OrbitCamera c;
    EXPECT_NEAR(glm::length(c.eye() - c.target), c.distance, 1e-2f);
    const glm::mat4 vp = c.projection(16.0f / 9.0f) * c.view();
    glm::vec4 t = vp * glm::vec4(c.target, 1.0f);
    t /= t.w;
    EXPECT_NEAR(t.x, 0.0f, 1e-5f);
    EXPECT_NEAR(t.y, 0.0f, 1e-5f);
    EXPECT_GT(t.z, 0.0f);
    EXPECT_LT(t.z, 1.0f);
    // a point anterior to the target (towards -y) appears above it: Vulkan's y points down
    glm::vec4 a = vp * glm::vec4(c.target + glm::vec3(0, -50, 0), 1.0f);
    a /= a.w;
    EXPECT_LT(a.y, t.y);
}

TEST(OrbitCamera, OrbitAndZoomStayInRange)
{
    OrbitCamera c;
    c.orbit(0.0f, 10.0f);
    EXPECT_LE(c.pitch, 1.55f);
    c.orbit(0.0f, -10.0f);
    EXPECT_GE(c.pitch, 0.05f);
    c.zoom(1e-6f);
    EXPECT_GE(c.distance, 200.0f);
    // the camera never goes below the table plane through the target
    EXPECT_LT(c.eye().y, c.target.y);
}

}  // namespace
}  // namespace echosim::scene

#include "scene/camera.hpp"

#include <cmath>

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

// target_on_screen moves the whole image: the target lands there, a point beside it keeps its
// offset from the target on screen, and depth is unchanged.
TEST(OrbitCamera, TheTargetLandsWhereItIsAskedOnScreen)
{
    OrbitCamera c;
    const glm::vec3 beside = c.target + glm::vec3(30, -20, 40);
    const auto ndc = [&](const glm::vec3& p) {
        glm::vec4 q = c.projection(1.2f) * c.view() * glm::vec4(p, 1.0f);
        return glm::vec3(q) / q.w;
    };
    const glm::vec3 t0 = ndc(c.target), b0 = ndc(beside);
    c.target_on_screen = glm::vec2(0.4f, -0.1f);
    const glm::vec3 t1 = ndc(c.target), b1 = ndc(beside);
    EXPECT_NEAR(t1.x, 0.4f, 1e-5f);
    EXPECT_NEAR(t1.y, -0.1f, 1e-5f);
    EXPECT_NEAR(b1.x - t1.x, b0.x - t0.x, 1e-5f);
    EXPECT_NEAR(b1.y - t1.y, b0.y - t0.y, 1e-5f);
    EXPECT_NEAR(t1.z, t0.z, 1e-6f);
    EXPECT_NEAR(b1.z, b0.z, 1e-6f);
    c.reset(c.target);  // the default view: at the centre again
    EXPECT_EQ(c.target_on_screen, glm::vec2(0.0f));
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

// follow: the target approaches the point as 1 - exp(-t / kFollowS), whatever the steps; the
// angle and distance stay as the user left them; reset gives the default view on a target
TEST(OrbitCamera, FollowApproachesThePointExponentiallyAndKeepsTheView)
{
    OrbitCamera c;
    c.orbit(0.4f, -0.2f);
    c.zoom(0.5f);
    const OrbitCamera before = c;
    const glm::vec3 start = c.target, point(100.0f, -20.0f, -400.0f);
    for (int i = 0; i < 60; ++i) c.follow(point, 1.0f / 120);  // 0.5 s in 60 steps
    const float expected = 1.0f - std::exp(-0.5f / OrbitCamera::kFollowS);
    const glm::vec3 moved = c.target - start, wanted = expected * (point - start);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(moved[k], wanted[k], 1e-3f * std::abs(point[k] - start[k]) + 1e-3f);
    EXPECT_EQ(c.yaw, before.yaw);
    EXPECT_EQ(c.pitch, before.pitch);
    EXPECT_EQ(c.distance, before.distance);
    // one step of 0.5 s goes as far as those 60
    OrbitCamera once = before;
    once.follow(point, 0.5f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(once.target[k], c.target[k], 1e-2f);
    // a bad dt moves nothing
    const glm::vec3 held = c.target;
    for (float bad : {0.0f, -1.0f, std::nanf(""), INFINITY}) c.follow(point, bad);
    EXPECT_EQ(c.target, held);

    c.reset(point);
    EXPECT_EQ(c.target, point);
    EXPECT_EQ(c.yaw, OrbitCamera{}.yaw);
    EXPECT_EQ(c.pitch, OrbitCamera{}.pitch);
    EXPECT_EQ(c.distance, OrbitCamera{}.distance);
}

}  // namespace
}  // namespace echosim::scene

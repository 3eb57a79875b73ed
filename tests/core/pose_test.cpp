#include "core/pose.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim {
namespace {

TEST(Pose, ParsesPositionAndQuaternion)
{
    // 90 degrees about z: (w, z) = (cos 45, sin 45)
    const Pose p = parse_pose("10,-20.5,30,0.70710678,0,0,0.70710678");
    EXPECT_FLOAT_EQ(p.position.x, 10.0f);
    EXPECT_FLOAT_EQ(p.position.y, -20.5f);
    EXPECT_FLOAT_EQ(p.position.z, 30.0f);
    // the probe's lateral axis x turns onto world +y
    const glm::vec3 x = p.axis_x();
    EXPECT_NEAR(x.x, 0.0f, 1e-6f);
    EXPECT_NEAR(x.y, 1.0f, 1e-6f);
    EXPECT_NEAR(x.z, 0.0f, 1e-6f);
}

TEST(Pose, RoundTripsThroughText)
{
    const Pose p = parse_pose("1.5,2.25,-3,0.5,0.5,0.5,0.5");
    const Pose q = parse_pose(format_pose(p));
    EXPECT_NEAR(glm::length(p.position - q.position), 0.0f, 1e-3f);
    EXPECT_NEAR(std::abs(glm::dot(p.orientation, q.orientation)), 1.0f, 1e-6f);
}

TEST(Pose, RejectsBadFieldsByName)
{
    auto message = [](const char* text) {
        try {
            parse_pose(text);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("1,2,3,1,0,0").find("qz is missing"), std::string::npos);
    EXPECT_NE(message("1,nan,3,1,0,0,0").find("field y"), std::string::npos);
    EXPECT_NE(message("1,2,3,inf,0,0,0").find("field qw"), std::string::npos);
    EXPECT_NE(message("1,2,abc,1,0,0,0").find("field z"), std::string::npos);
    EXPECT_NE(message("1,2,3,0.5,0,0,0").find("unit length"), std::string::npos);
    EXPECT_NE(message("1,2,3,1,0,0,0,9").find("more than 7"), std::string::npos);
    EXPECT_NE(message("").find("field x"), std::string::npos);
    // 1e39 is finite as a double but an infinity as a float: refused, not silently infinite
    EXPECT_NE(message("1e39,2,3,1,0,0,0").find("field x '1e39' is more than a kilometre"), std::string::npos);
    EXPECT_NE(message("1,2,-1e7,1,0,0,0").find("field z"), std::string::npos);
    EXPECT_EQ(message("1,2,-1e6,1,0,0,0"), "no error");
}

TEST(Pose, FromAxesIsOrthonormalAndKeepsTheBeam)
{
    const Pose p = pose_from_axes({1, 2, 3}, {1, 0.1f, 0}, {0, 0, -1});
    EXPECT_NEAR(glm::length(p.axis_y() - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(p.axis_x(), p.axis_y()), 0.0f, 1e-6f);
    // right-handed: z = x cross y
    EXPECT_NEAR(glm::length(glm::cross(p.axis_x(), p.axis_y()) - p.axis_z()), 0.0f, 1e-6f);
    const glm::vec4 origin = p.matrix() * glm::vec4(0, 0, 0, 1);
    EXPECT_FLOAT_EQ(origin.z, 3.0f);
}

}  // namespace
}  // namespace echosim

// A rigid pose in world (LPS millimetres): the probe frame's origin and orientation, as on the
// command line (`x,y,z,qw,qx,qy,qz`) and in trajectory rows.
#pragma once

#include <string>
#include <string_view>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace echosim {

struct Pose {
    glm::vec3 position{0.0f};                      // [mm]
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // unit quaternion (w, x, y, z)

    glm::mat4 matrix() const;  // probe frame to world
    glm::vec3 axis_x() const { return orientation * glm::vec3(1, 0, 0); }  // lateral, along the array
    glm::vec3 axis_y() const { return orientation * glm::vec3(0, 1, 0); }  // into the tissue
    glm::vec3 axis_z() const { return orientation * glm::vec3(0, 0, 1); }  // elevational
};

// A probe's position lies within a kilometre of the origin [mm]: a coordinate beyond is a typo or
// junk, and beyond float's range (1e39) it would silently become an infinity.
inline constexpr double kMaxPoseCoordinateMm = 1e6;

// Parses `x,y,z,qw,qx,qy,qz`. Throws std::invalid_argument naming the field when one is missing,
// not a finite number, a position beyond kMaxPoseCoordinateMm, or when the quaternion is not of
// unit length (within 1 %); the quaternion is then renormalised.
Pose parse_pose(std::string_view text);
std::string format_pose(const Pose& pose);

// The pose whose frame has the given axes (x lateral, y into the tissue), orthonormalised.
Pose pose_from_axes(glm::vec3 origin, glm::vec3 x_lateral, glm::vec3 y_beam);

// The probe at `pose` pushed `depth_mm` along its beam (+y, into the tissue); negative lifts it.
inline Pose pressed_along_beam(const Pose& pose, double depth_mm)
{
    Pose p = pose;
    p.position += float(depth_mm) * pose.axis_y();
    return p;
}

}  // namespace echosim

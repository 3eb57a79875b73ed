#include "core/pose.hpp"

#include "core/parse_number.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace echosim {

glm::mat4 Pose::matrix() const
{
    glm::mat4 m = glm::mat4_cast(orientation);
    m[3] = glm::vec4(position, 1.0f);
    return m;
}

Pose parse_pose(std::string_view text)
{
    static constexpr std::array<const char*, 7> names = {"x", "y", "z", "qw", "qx", "qy", "qz"};
    std::array<double, 7> v{};
    std::size_t pos = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::size_t comma = text.find(',', pos);
        const std::string_view field = text.substr(pos, comma == std::string_view::npos ? text.npos : comma - pos);
        if (field.empty())
            throw std::invalid_argument("pose field " + std::string(names[i]) + " is missing (expected x,y,z,qw,qx,qy,qz)");
        // parse_number reads whole tokens; tolerate blanks around a field
        const std::size_t b = field.find_first_not_of(' '), e = field.find_last_not_of(' ');
        const std::string_view trimmed = b == field.npos ? field.substr(0, 0) : field.substr(b, e - b + 1);
        if (!parse_number(trimmed, v[i]) || !std::isfinite(v[i]))
            throw std::invalid_argument("pose field " + std::string(names[i]) + " is not a finite number: '" +
                                        std::string(field) + "'");
        if (i < 3 && std::abs(v[i]) > kMaxPoseCoordinateMm)
            throw std::invalid_argument("pose field " + std::string(names[i]) + " '" + std::string(field) +
                                        "' is more than a kilometre from the origin (|" + std::string(names[i]) + "| <= 1e6 mm)");
        if (i + 1 < names.size() && comma == std::string_view::npos)
            throw std::invalid_argument("pose field " + std::string(names[i + 1]) +
                                        " is missing (expected x,y,z,qw,qx,qy,qz)");
        if (i + 1 == names.size() && comma != std::string_view::npos)
            throw std::invalid_argument("pose has more than 7 fields (expected x,y,z,qw,qx,qy,qz)");
        pos = comma + 1;
    }
    const double norm = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
    if (std::abs(norm - 1.0) > 0.01)
        throw std::invalid_argument("pose quaternion (qw,qx,qy,qz) is not of unit length: |q| = " + std::to_string(norm));
    Pose p;
    p.position = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    p.orientation = glm::quat(float(v[3] / norm), float(v[4] / norm), float(v[5] / norm), float(v[6] / norm));
    return p;
}

std::string format_pose(const Pose& p)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.3f,%.3f,%.3f,%.6f,%.6f,%.6f,%.6f", p.position.x, p.position.y, p.position.z,
                  p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
    return buf;
}

Pose pose_from_axes(glm::vec3 origin, glm::vec3 x_lateral, glm::vec3 y_beam)
{
    const glm::vec3 y = glm::normalize(y_beam);
    const glm::vec3 z = glm::normalize(glm::cross(x_lateral, y));
    const glm::vec3 x = glm::cross(y, z);
    Pose p;
    p.position = origin;
    p.orientation = glm::normalize(glm::quat_cast(glm::mat3(x, y, z)));
    return p;
}

}  // namespace echosim

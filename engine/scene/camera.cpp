#include "scene/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace echosim::scene {

glm::vec3 OrbitCamera::eye() const
{
    // horizontal directions: +z towards the head, +x to the patient's left
    const glm::vec3 horizontal = std::sin(yaw) * glm::vec3(1, 0, 0) - std::cos(yaw) * glm::vec3(0, 0, 1);
    return target + distance * (std::cos(pitch) * horizontal + std::sin(pitch) * up);
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target, up); }

glm::mat4 OrbitCamera::projection(float aspect) const
{
    // near and far bracket a room-sized scene in millimetres; depth maps to [0, 1]
    glm::mat4 p = glm::perspectiveRH_ZO(fov_y, aspect, 20.0f, 20000.0f);
    p[1][1] *= -1.0f;  // Vulkan's clip space has y pointing down
    // the image shifted in clip space (x' = x + s w), so the target lands at target_on_screen
    glm::mat4 shift(1.0f);
    shift[3][0] = target_on_screen.x;
    shift[3][1] = target_on_screen.y;
    return shift * p;
}

void OrbitCamera::orbit(float d_yaw, float d_pitch)
{
    yaw += d_yaw;
    pitch = std::clamp(pitch + d_pitch, 0.05f, 1.55f);
}

void OrbitCamera::zoom(float factor) { distance = std::clamp(distance * factor, 200.0f, 4000.0f); }

void OrbitCamera::follow(const glm::vec3& point, float dt_s)
{
    if (!(dt_s > 0.0f) || !std::isfinite(dt_s)) return;
    const float share = 1.0f - std::exp(-dt_s / kFollowS);
    target += share * (point - target);
}

void OrbitCamera::reset(const glm::vec3& target_now)
{
    *this = OrbitCamera{};
    target = target_now;
}

}  // namespace echosim::scene

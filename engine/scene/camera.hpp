// An orbit camera around a target point. "Up" on screen is the patient's anterior (-y in LPS),
// since the patient lies supine on the table. Projection follows Vulkan: depth in [0, 1], y down.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace echosim::scene {

struct OrbitCamera {
    // default: the examiner's view, standing at the patient's right beside the knee, looking at
    // the probe on the right thigh with the knee, the lower legs and the other leg in sight
    glm::vec3 target{-40.0f, -40.0f, -260.0f};  // [mm]
    float yaw = -0.30f;        // [rad] about the up axis; 0 looks from the feet towards the head
    float pitch = 1.05f;       // [rad] above the table plane
    float distance = 1000.0f;  // [mm]
    float fov_y = 0.65f;       // [rad]
    // Where the target appears in the view, in normalised device coordinates (x right, y down, the
    // view's edges at -1 and 1; 0: its centre): a view part covered (the trainer's exam panel over
    // the leg's view) shows the target in the middle of what is left (projection() shifts the image).
    glm::vec2 target_on_screen{0.0f, 0.0f};

    static constexpr glm::vec3 up{0.0f, -1.0f, 0.0f};

    glm::vec3 eye() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;

    void orbit(float d_yaw, float d_pitch);  // pitch is kept between just above the table and overhead
    void zoom(float factor);                 // distance kept within [200, 4000] mm
    // Moves the target towards `point` [mm] over `dt_s`, as a camera operator keeps the probe in
    // frame: an exponential approach with time constant kFollowS, so a probe slid down the thigh
    // is followed smoothly and a probe held still is centred; the angle and distance stay the
    // user's. A dt that is not finite and positive moves nothing.
    void follow(const glm::vec3& point, float dt_s);
    static constexpr float kFollowS = 0.35f;  // [s]
    // The default view again (angle, distance, field of view, the target at the centre), looking at
    // `target_now`.
    void reset(const glm::vec3& target_now);
};

}  // namespace echosim::scene

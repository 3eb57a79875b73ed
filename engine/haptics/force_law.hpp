// The force the haptic loop renders (paper §5.2, Balaniuk's buffer model): the physics' local contact
// model (physics/local_contact_model.hpp: the skin under the probe as a plane with a local stiffness
// and damping) evaluated at the probe's pose now, within what the device can render stably.
// One force computation is a few dot products: the loop can afford it every millisecond.
#pragma once

#include <Eigen/Core>

#include "device/device.hpp"
#include "physics/local_contact_model.hpp"

namespace echosim::haptics {

// What the device can render; 0: no limit (a device without force feedback: the force is shown, not felt).
struct ForceLimits {
    double max_force_N = 0;
    double max_stiffness_N_per_mm = 0;
    double max_damping_N_s_per_mm = 0;
    static ForceLimits of(const device::Capabilities& c)
    {
        return {c.max_force_N, c.max_stiffness_N_per_mm, c.max_damping_N_s_per_mm};
    }
};

struct HapticForce {
    double along_N = 0;                             // the tissue's push along the probe's axis, >= 0
    Eigen::Vector3d world_N = Eigen::Vector3d::Zero();  // on the probe (the user's hand), world [N]
    bool in_contact = false;
    bool clamped = false;  // a limit cut it
};

// With the local model: the plane's force at the face now (`face` [mm], `velocity` [mm/s]), its
// stiffness and damping first cut to the device's, the force then to its largest.
HapticForce local_model_force(const physics::LocalContactModel& m, const Eigen::Vector3d& face, const Eigen::Vector3d& velocity,
                              const ForceLimits& limits);
// A new local model arrives with each physics step, and what it says at the probe's pose differs
// from what the last one said (the physics saw more than a plane can predict: the probe sliding
// onto stiffer tissue, a contact patch that grew). Rendered as is, that difference would be a step
// in the force every physics period, felt as the trembling the local model is there to remove. So
// at each refresh the difference is kept as an offset that fades out linearly over one physics
// period (the time since the previous refresh): the force stays continuous, and follows the new
// model fully one period later. Plain data; the haptic thread's own.
struct RefreshBlend {
    double offset_N = 0;
    double since_s = 0;  // the refresh's time
    double over_s = 0;   // the fade's length
    // at time t the model changed: it gave `before_N` and now gives `after_N` at the probe's pose
    void refresh(double t_s, double before_N, double after_N, double period_s);
    double apply(double force_N, double t_s) const;
};

// Without it (the paper's comparison): the force of the last physics step, held until the next.
HapticForce held_physics_force(const physics::LocalContactModel& m, const ForceLimits& limits);

}  // namespace echosim::haptics

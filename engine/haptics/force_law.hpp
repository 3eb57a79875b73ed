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
// Without it (the paper's comparison): the force of the last physics step, held until the next.
HapticForce held_physics_force(const physics::LocalContactModel& m, const ForceLimits& limits);

}  // namespace echosim::haptics

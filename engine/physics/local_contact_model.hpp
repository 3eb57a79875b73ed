// What the physics hands the haptic thread after every step (DESIGN.md §1, haptics; paper §5.2):
// Balaniuk's buffer model, the skin under the probe as a plane that pushes back with a local
// stiffness and damping, so the 1 kHz haptic loop can render a smooth force between (and beyond)
// the physics steps from the probe's own pose:
//     F(face', v) = max(0, force + stiffness (axis . (face' - face)) + damping (axis . v - speed))
// with face' the probe's face centre now and v its velocity [mm/s], along the probe axis. The
// step's force already holds the damping at the speed the probe had then (`speed`): only a change
// of speed adds to it.
//
// The stiffness is the quasi-static response to the probe advancing along its axis: at each skin
// node under the probe, the penalty contact in series with the tissue column beneath (its
// non-linear spring along the normal, its shear spring across), projected on the axis, summed over
// the nodes. The surface springs' coupling is left out: the fitted lambda is three orders of
// magnitude below the columns' stiffness (tissue/tissue_model.hpp), and a test bounds the
// prediction against the full dynamics.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "physics/compiled_model.hpp"
#include "physics/tissue_state.hpp"

namespace echosim::physics {

struct LocalContactModel {
    double time = 0;  // simulated time of the step it comes from [s]
    std::int64_t step = 0;
    bool in_contact = false;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // probe +y in world: the plane's normal, into the tissue
    Eigen::Vector3d face = Eigen::Vector3d::Zero();   // the probe's face centre at that step [mm]
    double force = 0;      // the tissue's push on the probe along the axis [N]
    double stiffness = 0;  // d force / d advance along the axis [N/mm]
    double damping = 0;    // d force / d speed along the axis [N s/mm]
    double speed = 0;      // the probe's speed along the axis at that step [mm/s]

    // The force the model gives for the face at `face_now` moving at `velocity` [N].
    double force_at(const Eigen::Vector3d& face_now, const Eigen::Vector3d& velocity) const
    {
        if (!in_contact) return 0.0;
        const double f = force + stiffness * axis.dot(face_now - face) + damping * (axis.dot(velocity) - speed);
        return f > 0.0 ? f : 0.0;
    }
};

// The model of the state's last step on `model` (contacts found, linearisation up to date). Uses
// state.node_scratch; allocates nothing.
LocalContactModel local_contact_model(const CompiledModel& model, TissueState& state);

}  // namespace echosim::physics

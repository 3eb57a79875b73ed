// The mechanics of a simulated force-feedback arm's handle (device/simulated_arm.hpp): a point mass
// in the arm's workspace, with viscous and dry (Coulomb) friction, end stops at the workspace's
// faces, pushed by the force the arm renders and held by a simulated hand through a virtual
// coupling (a spring and a damper between where the hand wants the handle and where it is). So a
// constant force F against a hand held still leaves the handle F/k from the hand, and the same force
// on a handle let go (k = 0) drives it at (|F| - Fc)/c once the mass has caught up.
//
// Units: mm, s, N, kg (a mass in kg moved by N accelerates at 1000 F/m mm/s^2). Plain data and one
// function: the servo thread and the tests step the same code.
#pragma once

#include <Eigen/Core>

namespace echosim::device {

struct ArmParameters {
    double mass_kg = 0.1;                  // the handle and the links that move with it
    double viscous_N_s_per_mm = 0.002;     // bearing and motor friction, along the velocity
    double coulomb_N = 0.03;               // dry friction: a force below it does not start the handle
    double coupling_N_per_mm = 0.3;        // the hand's grip: its spring
    double coupling_N_s_per_mm = 0.002;    // and its damper (the hand holding still)
    Eigen::Vector3d workspace_mm = Eigen::Vector3d(160, 120, 70);  // a box about the origin: end stops
};

struct ArmState {
    Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity_mm_s = Eigen::Vector3d::Zero();
};

// One step of `dt_s`: the hand's target `hand_mm`, the arm's rendered force `force_N` (held over the
// step). Semi-implicit: the dampers are taken at the step's end (stable for any step), the springs at
// its start, dry friction with the dampers as an impulse that can stop the handle but never reverse
// it (so a steady slide is exactly (|F| - Fc)/c); the handle stops at the workspace's faces. `p`
// must be valid (invalid_field(p) is "").
void step(const ArmParameters& p, ArmState& s, const Eigen::Vector3d& hand_mm, const Eigen::Vector3d& force_N, double dt_s);

// "" when the parameters make a handle that can move (a positive mass, no negative friction), else
// which field is wrong
const char* invalid_field(const ArmParameters& p);

}  // namespace echosim::device

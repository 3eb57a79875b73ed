#include "device/arm_dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace echosim::device {

void step(const ArmParameters& p, ArmState& s, const Eigen::Vector3d& hand_mm, const Eigen::Vector3d& force_N, double dt_s)
{
    const double per_N = 1000.0 * dt_s / p.mass_kg;  // [mm/s] of velocity one newton gives over the step
    // explicit: the rendered force and the hand's spring; implicit: the friction's and the hand's dampers
    const Eigen::Vector3d pushed = force_N + p.coupling_N_per_mm * (hand_mm - s.position_mm);
    const double damped = 1.0 + per_N * (p.viscous_N_s_per_mm + p.coupling_N_s_per_mm);
    Eigen::Vector3d v = (s.velocity_mm_s + per_N * pushed) / damped;
    // dry friction, in the same implicit solve: against the motion, and at most enough to stop it
    const double speed = v.norm(), stop = per_N * p.coulomb_N / damped;
    v = speed <= stop ? Eigen::Vector3d::Zero() : Eigen::Vector3d(v * (1.0 - stop / speed));
    s.velocity_mm_s = v;
    s.position_mm += dt_s * v;
    // end stops: the handle rests against a face, its velocity into it gone
    const Eigen::Vector3d half = 0.5 * p.workspace_mm;
    for (int i = 0; i < 3; ++i) {
        if (s.position_mm[i] > half[i]) {
            s.position_mm[i] = half[i];
            s.velocity_mm_s[i] = std::min(s.velocity_mm_s[i], 0.0);
        } else if (s.position_mm[i] < -half[i]) {
            s.position_mm[i] = -half[i];
            s.velocity_mm_s[i] = std::max(s.velocity_mm_s[i], 0.0);
        }
    }
}

const char* invalid_field(const ArmParameters& p)
{
    auto ok = [](double v, bool positive) { return std::isfinite(v) && (positive ? v > 0.0 : v >= 0.0); };
    if (!ok(p.mass_kg, true)) return "mass_kg";
    if (!ok(p.viscous_N_s_per_mm, false)) return "viscous_N_s_per_mm";
    if (!ok(p.coulomb_N, false)) return "coulomb_N";
    if (!ok(p.coupling_N_per_mm, false)) return "coupling_N_per_mm";
    if (!ok(p.coupling_N_s_per_mm, false)) return "coupling_N_s_per_mm";
    if (!(ok(p.workspace_mm.x(), true) && ok(p.workspace_mm.y(), true) && ok(p.workspace_mm.z(), true))) return "workspace_mm";
    return "";
}

}  // namespace echosim::device

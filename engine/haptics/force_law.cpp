#include "haptics/force_law.hpp"

#include <algorithm>

namespace echosim::haptics {
namespace {

double capped(double value, double limit) { return limit > 0.0 ? std::min(value, limit) : value; }

HapticForce along_axis(const physics::LocalContactModel& m, double f, const ForceLimits& limits, bool clamped)
{
    HapticForce out;
    out.in_contact = m.in_contact;
    const double pushed = std::max(f, 0.0);
    out.along_N = capped(pushed, limits.max_force_N);
    out.clamped = clamped || out.along_N < pushed;
    out.world_N = -out.along_N * m.axis;  // the tissue pushes the probe back out, against its beam
    return out;
}

}  // namespace

HapticForce local_model_force(const physics::LocalContactModel& m, const Eigen::Vector3d& face, const Eigen::Vector3d& velocity,
                              const ForceLimits& limits)
{
    physics::LocalContactModel renderable = m;
    renderable.stiffness = capped(m.stiffness, limits.max_stiffness_N_per_mm);
    renderable.damping = capped(m.damping, limits.max_damping_N_s_per_mm);
    return along_axis(m, renderable.force_at(face, velocity), limits, renderable.stiffness < m.stiffness || renderable.damping < m.damping);
}

void RefreshBlend::refresh(double t_s, double before_N, double after_N, double period_s)
{
    offset_N = apply(before_N, t_s) - after_N;  // a refresh during a fade continues from where it is
    since_s = t_s;
    over_s = std::clamp(period_s, 1e-3, 0.05);
}

double RefreshBlend::apply(double force_N, double t_s) const
{
    if (over_s <= 0.0) return force_N;
    const double w = std::max(0.0, 1.0 - (t_s - since_s) / over_s);
    return std::max(0.0, force_N + w * offset_N);
}

HapticForce held_physics_force(const physics::LocalContactModel& m, const ForceLimits& limits)
{
    return along_axis(m, m.in_contact ? m.force : 0.0, limits, false);
}

}  // namespace echosim::haptics

#include "haptics/probe_mapping.hpp"

#include <algorithm>
#include <numbers>

#include "contact/probe_contact.hpp"

namespace echosim::haptics {
namespace {

// the contact's own conversion of a pose, renormalised in double
ProbeFace from_pose(const Pose& p)
{
    const contact::ProbeState s = contact::probe_at(p);
    return {s.position, s.orientation.normalized()};
}

}  // namespace

ProbeMapping::ProbeMapping(const scene::LegModel& leg, const WorkspaceMapping& workspace) : leg_(leg), workspace_(workspace)
{
    const ProbeFace centre = from_pose(leg_.probe_rest_pose(0.5f, 0.5f));
    anchor_ = centre.position - workspace_.anchor_lift_mm * centre.beam();
    // device x -> probe x (lateral), device y (up) -> probe -y (out of the skin), device z -> probe -z
    // (x cross y: a rotation, 180 degrees about the probe's x)
    device_to_probe_ = Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()));
    to_world_ = centre.orientation * device_to_probe_;
}

ProbeFace ProbeMapping::face(const device::DeviceSample& s) const
{
    switch (s.control) {
    case device::Control::surface: {
        const device::SurfacePlacement& p = s.surface;
        ProbeFace f = from_pose(leg_.probe_rest_pose(float(p.u), float(p.v)));
        // the twist about the beam (probe y) first: the tilts are then about the turned probe's axes
        f.orientation = f.orientation * Eigen::AngleAxisd(p.twist_rad, Eigen::Vector3d::UnitY()) *
                        Eigen::AngleAxisd(p.fan_rad, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(p.rock_rad, Eigen::Vector3d::UnitZ());
        f.position += p.press_mm * f.beam();
        return f;
    }
    case device::Control::workspace: {
        ProbeFace f;
        f.position = anchor_ + to_world_ * (workspace_.scale * s.position);
        // the handle upright (identity) holds the probe as it rests on the middle of the patch
        f.orientation = (to_world_ * s.orientation * device_to_probe_.conjugate()).normalized();
        return f;
    }
    case device::Control::world: break;
    }
    ProbeFace f;
    f.position = s.position;
    f.orientation = s.orientation;
    return f;
}

device::SurfaceLimits exam_limb_surface(const scene::LegModel& leg)
{
    const scene::ExamPatch& w = leg.patch();
    const auto u_at = [&](float z_mm) { return double(leg.limb_t_at_z(z_mm) - w.t0) / double(w.t1 - w.t0); };
    const double turn = 2.0 * std::numbers::pi / double(w.theta1 - w.theta0);  // a full turn in v
    const double from = u_at(kExamLimbFromZ_mm), to = u_at(kExamLimbToZ_mm);
    return {std::min(from, to), std::max(from, to), 0.5 - 0.5 * turn, 0.5 + 0.5 * turn};
}

Eigen::Vector3d ProbeMapping::to_device(const Eigen::Vector3d& force_world, device::Control control) const
{
    return control == device::Control::workspace ? Eigen::Vector3d(to_world_.conjugate() * force_world) : force_world;
}

}  // namespace echosim::haptics

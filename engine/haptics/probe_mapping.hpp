// From a device's sample to the probe's face in world, and from a force in world back to the
// device's frame (DESIGN.md §2: world is LPS millimetres; the probe frame is x lateral, y into the
// tissue). Immutable once made; the haptic thread calls it every tick: no allocation.
//   - surface control: the probe rests on the exam patch at (u, v) (scene::LegModel::probe_rest_pose;
//     past [0, 1] along and around the limb beyond the patch), turned about its beam (twist:
//     transverse to longitudinal), tilted about its own lateral axis (fan) and elevational axis
//     (rock) around the face centre, then pressed along its tilted beam;
//   - workspace control (a force-feedback arm): the handle's position, scaled, about an anchor 20 mm
//     above the middle of the exam patch, with the device's axes (x right, y up, z towards the user,
//     as OpenHaptics and Force Dimension have them) turned onto the probe's there (x lateral, y down
//     the beam, so up is out of the skin); the handle's rotation turned the same way;
//   - world control: as given.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "device/device.hpp"
#include "scene/leg.hpp"

namespace echosim::haptics {

struct ProbeFace {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();               // face centre, world [mm]
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // probe frame to world
    Eigen::Vector3d beam() const { return orientation * Eigen::Vector3d::UnitY(); }
};

struct WorkspaceMapping {
    double scale = 1.0;            // world mm per device mm
    double anchor_lift_mm = 20.0;  // the workspace origin above the middle of the exam patch
};

// The exam limb's course for a surface device (device::SurfaceLimits) in the (u, v) of `leg`'s
// patch: along the limb from just above the groin crease (the deep vein is modelled from 15 mm
// above it) to below the popliteal trifurcation (z about -485 mm), and once around the limb,
// so the popliteal fossa behind the knee is reached from the home patch's frame.
inline constexpr float kExamLimbFromZ_mm = 20.0f, kExamLimbToZ_mm = -520.0f;
device::SurfaceLimits exam_limb_surface(const scene::LegModel& leg);

class ProbeMapping {
public:
    // keeps a reference to `leg`, which must outlive it
    explicit ProbeMapping(const scene::LegModel& leg, const WorkspaceMapping& workspace = {});

    ProbeFace face(const device::DeviceSample& s) const;
    // a force in world [N] in the frame of a device of `control` (workspace axes for an arm; world
    // for the others, which have no force output of their own)
    Eigen::Vector3d to_device(const Eigen::Vector3d& force_world, device::Control control) const;

private:
    const scene::LegModel& leg_;
    WorkspaceMapping workspace_;
    Eigen::Vector3d anchor_ = Eigen::Vector3d::Zero();
    Eigen::Quaterniond device_to_probe_ = Eigen::Quaterniond::Identity();  // device axes to the probe's
    Eigen::Quaterniond to_world_ = Eigen::Quaterniond::Identity();         // device axes to world
};

}  // namespace echosim::haptics

#include "app/simulation.hpp"

#include <algorithm>

#include "core/assets.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::app {

tissue::TissueModel load_simulation_model(const scene::LegModel& leg, int refine)
{
    const tissue::TissueModel fitted = tissue::read_tissue_model(asset_path("models/thigh.json"));
    tissue::TissueModel model = tissue::build_tissue_model(leg, fitted.samples, refine);
    model.fit = fitted.fit;
    model.provenance = fitted.provenance;
    return model;
}

physics::ProbeCommand pressed(const Pose& pose, double press_mm, double press_speed_mm_s)
{
    physics::ProbeCommand c;
    c.active = true;
    c.orientation = Eigen::Quaterniond(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
    const Eigen::Vector3d beam = c.orientation * Eigen::Vector3d::UnitY();
    c.position = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z) + press_mm * beam;
    c.velocity = press_speed_mm_s * beam;
    return c;
}

void press_and_settle(physics::PhysicsRunner& runner, const Pose& pose, double press_mm, double settle_s)
{
    constexpr double ramp = 0.1, dt = 1e-3;
    for (double t = dt; t <= settle_s + 0.5 * dt; t += dt) {
        const bool pressing = t < ramp;
        runner.command(pressed(pose, press_mm * std::min(1.0, t / ramp), pressing ? press_mm / ramp : 0.0));
        runner.step_to(t);
    }
}

}  // namespace echosim::app

// The tissue simulation as the commands use it: the shipped fitted model at the resolution the
// physics runs at in real time, and the probe command for a pose pressed some depth into the skin.
#pragma once

#include "core/pose.hpp"
#include "physics/physics_runner.hpp"
#include "scene/leg.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::app {

// 2500 nodes: the largest grid that steps at 1 kHz on one core (bench/RESULTS.md, physics).
inline constexpr int kSimulationRefine = 7;

// assets/models/thigh.json's fitted parameters on our leg's patch; throws naming the file if it is
// missing or malformed.
tissue::TissueModel load_simulation_model(const scene::LegModel& leg, int refine = kSimulationRefine);

// The probe at `pose` pushed `press_mm` along its beam.
physics::ProbeCommand pressed(const Pose& pose, double press_mm, double press_speed_mm_s = 0.0);

// Headless: presses the probe in over 0.1 s and lets the tissue settle until `settle_s`.
void press_and_settle(physics::PhysicsRunner& runner, const Pose& pose, double press_mm, double settle_s = 0.4);

}  // namespace echosim::app

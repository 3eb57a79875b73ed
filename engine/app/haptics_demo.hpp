// The paper's Fig. 8, reproduced (§5.2): a scripted probe comes down onto the thigh, presses in,
// slides across the skin and lifts off, while the haptic loop ticks at 1 kHz and the physics steps at
// 100 Hz, as in the paper. Every tick logs two forces from the same run: the one rendered from the
// local contact model, and the last physics step's force held until the next step (what a loop
// without the local model would send). Lock-step on simulated time: the same figures every run.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "device/trajectory.hpp"
#include "runner/runner.hpp"
#include "scene/leg.hpp"

namespace echosim::app {

struct SlideScript {
    double u = 0.5;                   // along the thigh, where the probe slides across it
    double v_from = 0.25, v_to = 0.75;  // around the thigh
    double lift_mm = 4;               // above the skin at the start and the end
    double press_mm = 6;              // into the skin while it slides
    double approach_s = 0.5, hold_s = 0.3, slide_s = 2.0;
    double row_s = 0.005;             // between the trajectory's rows
};

// The script as a world trajectory over `leg`, and the times the probe is pressed at least 1 mm in
// (on the skin for certain: the window in which a lost contact counts).
struct SlideTrajectory {
    device::Trajectory trajectory;
    double on_skin_from_s = 0, on_skin_to_s = 0;
};
SlideTrajectory make_slide_trajectory(const scene::LegModel& leg, const SlideScript& script = {});
// The script there and back: across the thigh from v_from to v_to, then from v_to back to v_from,
// pressing and lifting each way; it ends where it starts (lifted above v_from), so a device can
// loop it without a jump (device::ScriptedDevice::Playback::loop). 7.2 s with the defaults.
device::Trajectory make_round_trip_trajectory(const scene::LegModel& leg, const SlideScript& script = {});
// How long one round trip lasts [s].
double round_trip_s(const SlideScript& script = {});

struct ForceLogRow {
    double t_s = 0;
    double local_model_N = 0;    // rendered from the local model
    double held_physics_N = 0;   // the last physics step's force, held
    long long physics_step = 0;
    bool on_skin = false;
};

struct ForceCurveSummary {
    double max_jump_N = 0;     // the largest change from one tick (1 ms) to the next
    int lost_contacts = 0;     // on the skin, the force fell to zero
};

struct Fig8Result {
    std::vector<ForceLogRow> rows;
    ForceCurveSummary local_model, held_physics;
    double physics_hz = 0, haptic_hz = 0;
};

// Runs the script; physics_hz is the physics' rate (the paper's 100), the loop runs at 1 kHz.
// It is the runner's configuration without a frame (runner/runner.hpp), one lock-step step per tick;
// `observers` join the demo's own (tests count its steps).
Fig8Result run_fig8(const SlideScript& script = {}, double physics_hz = 100.0,
                    std::vector<std::shared_ptr<runner::Observer>> observers = {});

// force_log.csv, force.png (both curves), summary.json in `dir` (made if missing). Throws
// std::runtime_error naming the file it could not write.
void write_fig8(const Fig8Result& r, const std::filesystem::path& dir);

}  // namespace echosim::app

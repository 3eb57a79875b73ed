// A scripted exam (DESIGN.md §3, "trajectory"): the probe's poses over time as a trajectory CSV,
// with an optional last column `call` (empty, `compressible` or `not-compressible`) carrying the
// trainee's calls, so that one file an instructor can read and edit performs a whole exam. The pose
// columns are handed to device::Trajectory unchanged (it checks them); this reads the calls.
//
// plan_exam writes such a script from the stations' truth: the correct exam, or one that makes one
// classic error at one station (issue 31 item 5: the shipped trajectories).
#pragma once

#include <string>
#include <vector>

#include "core/pose.hpp"
#include "exam/exam_report.hpp"
#include "exam/station_truth.hpp"

namespace echosim::exam {

struct TimedCall {
    double t_s = 0;
    Call call = Call::none;
};

struct ScriptedPose {
    double t_s = 0;
    Pose pose;
};

struct ExamScript {
    std::vector<ScriptedPose> poses;
    std::vector<TimedCall> calls;
};

// The script's text split: the pose columns as a trajectory CSV (device::Trajectory's header and
// rows, line for line, so its messages' line numbers hold) and the calls. Throws
// std::invalid_argument naming `source`, the line and the value when a call is not one of the three.
struct SplitScript {
    std::string trajectory_csv;
    std::vector<TimedCall> calls;
};
SplitScript split_exam_script(const std::string& text, const std::string& source);

// The script as text: the trajectory header plus `,call`, 17 significant digits.
std::string format_exam_script(const ExamScript& script);

// How a planned exam goes wrong, at station `at` (ignored for `correct`).
enum class PlanError { none, skip, light_press, oblique, artery, excessive, mimic_called };
const char* plan_error_name(PlanError e);  // "correct", "skip", "light-press", "oblique", "artery", "excessive", "mimic-called"

struct PlanOptions {
    PlanError error = PlanError::none;
    std::size_t at = 0;        // the station the error happens at
    double lift_mm = 8.0;      // above the skin between stations [mm]
    double travel_s = 0.8;     // from one station to the next, lifted [s]
    double lower_s = 0.3;      // onto the skin [s]
    double press_s = 0.8;      // pressing in [s]
    double hold_s = 0.4;       // holding the deepest press; the call is made at its end [s]
    double release_s = 0.4;    // back to the skin [s]
    // between stations whose beams differ by more than far_turn_deg (the thigh's front to the back
    // of the knee) the probe goes round the limb, far_lift_mm out, not through it
    double far_turn_deg = 20.0;
    double far_lift_mm = 80.0;
    // and crosses at this speed at most [mm/s]: half what the physics lets a probe command sweep
    // (physics/probe_sweep.hpp), so the probe is where the script says when it comes down
    double far_speed_mm_s = 250.0;
    double light_fraction = 0.25;  // light_press: this fraction of the station's depth
    double excessive_factor = 1.8; // excessive: this times the station's depth, unless
    double excessive_press_mm = -1.0;  // excessive: this depth (< 0: the factor's; `case plan` finds one past the limit)
    double oblique_deg = 30.0;     // oblique: the plane tilted about the array this far
    // oblique: the depth pressed at the tilted pose (< 0: the station's own); a tilted face digs its
    // edge in, so the same force wants a shallower press (`echosim case plan` finds it on the tissue)
    double oblique_press_mm = -1.0;
};

// The exam over the stations in order: lifted travel to above each, down onto the skin, pressed
// `press_mm[i]` along the beam, held, the call the truth asks for made, released. The probe starts
// lifted above the first station. The calls of a correct exam are right; the error's station gets
// what its error does (a skipped station is neither visited nor called; mimic_called calls the
// healthy station not compressible).
ExamScript plan_exam(const std::vector<StationTruth>& stations, const std::vector<double>& press_mm, const PlanOptions& options = {});
// The rest pose tilted `deg` about its array's axis, the face still centred on the same skin point.
Pose tilted_about_array(const Pose& rest, double deg);
// Whether the probe must go round the limb from the rest pose `from` to `to` (their beams more than
// options.far_turn_deg apart).
bool turns_far(const Pose& from, const Pose& to, const PlanOptions& options);

}  // namespace echosim::exam

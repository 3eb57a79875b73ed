// The exam's scorer (DESIGN.md §1, "trainer"; issue 31 item 4): it watches the session step by
// step and judges each station of the case's protocol on the simulation's truth (STYLE.md 16), never
// on the image alone:
//   - reached: the vein's axis crosses the image plane within ScoringBands::reach_mm of the beam's
//     centre line, within kAlongToleranceMm of the station along the vein (where the beam's centre
//     line passes nearest it), the plane within transverse_deg of transverse, the probe in contact;
//     a probe within reach of two stations is at the nearer one;
//   - pressed: the deepest press while there: the highest force held for kPressHeldS (the least
//     force over that long a run of samples at the station, so one sample's spike, a jab or the
//     contact's ripple, is not a press the protocol asks for), against the case's adequate and
//     excessive bands, and the session's echo frame at the end of that held press, kept to be
//     imaged afterwards;
//   - compression: the vein's interior (lumen and thrombus) and the artery's lumen in the deformed
//     labels at the deepest press against the same plane at rest (measure_compression), so the walls
//     meeting is measured, not guessed;
//   - the trainee's call (compressible or not), against the truth under the station.
// Errors flagged: a skipped station, too little pressure, the wrong vessel pressed (the artery or
// the great saphenous vein under the beam instead of the vein), an oblique plane, excessive force, a
// mimic called a clot, a wrong call. Motion: time, the probe's path, its angle from transverse.
//
// Threads: one (the runner's driver thread, or a test). No allocation per step beyond the force
// trace's growth.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "echo/echo_frame.hpp"
#include "exam/exam_report.hpp"
#include "exam/scenario.hpp"
#include "exam/station_truth.hpp"

namespace echosim::exam {

// How far along the vein from a station the image plane may cross it and still be at that station
// [mm]: half the extended protocol's 2 cm spacing, so neighbouring stations never overlap.
inline constexpr double kAlongToleranceMm = 10.0;
// The probe touches the skin above this force [N].
inline constexpr double kContactForceN = 0.2;
// A press counts for the wrong-vessel and oblique checks from this fraction of the adequate force.
inline constexpr double kPressingFraction = 0.5;
// The vein's walls met at a station's deepest press: its lumen in the deformed labels at most this
// fraction of its rest. The protocol's adequate pressure is the walls meeting, whatever the force
// took: a press that closed the vein under the case's adequate force was pressed enough (a slim
// trainee's patient, a light hand) and is not flagged too little; a vein left open (or one that a
// thrombus holds open) is judged by the force alone. A normal vein pressed adequately closes to
// 0.03 or less in the shipped cases (bench/RESULTS.md), a light press leaves a quarter or more.
inline constexpr double kWallsMetRatio = 0.1;
// A press is flagged excessive once the force has stayed above the case's excessive limit this long
// at the station [s]: a trainee pressing too hard holds it; one frame's spike (the contact's ripple
// at the deepest presses, bench/RESULTS.md "The contact's long sides"; a jolt of the hand) is not
// what the protocol warns of. Four samples at 60 frames a second.
inline constexpr double kExcessiveHoldS = 0.05;

// A station's deepest press is the highest force held this long there [s]: the least force over a
// run of samples at the station that spans it (kExcessiveHoldS's four samples at 60 frames a
// second). A trainee's press held for the call passes; a spike above what the hand holds does not
// raise the force judged, nor pick the image the compression is measured on.
inline constexpr double kPressHeldS = 0.05;

// One step as the scorer sees it: the session's view, reduced to plain values.
struct ExamSample {
    double time_s = 0;
    Pose face;                  // the probe's face where it is (pressed)
    double force_N = 0;         // the tissue's push on the probe
    const echo::EchoFrame* echo = nullptr;  // the image's input at this step (kept at the deepest press)
    double image_depth_mm = kLinearProbe.image_depth_mm;  // how deep the trainee's image reaches (the scanner's depth)
};

// What the labels say at one station's deepest press (measure_compression).
struct Compression {
    double vein_rest_mm2 = 0, vein_pressed_mm2 = 0;
    double artery_rest_mm2 = 0, artery_pressed_mm2 = 0;
};

// The tissue codes of an image made from `frame` (the CPU twin's labels, row-major columns x rows).
using LabelImager = std::function<std::vector<std::uint8_t>(const echo::EchoFrame& frame)>;

// The vein's interior and the artery's lumen in the labels imaged at `pressed` and at the same
// plane unpressed (its columns emptied), counted within the vessel's own columns (its projection
// +- 1.5 radii across the array), in mm^2 of the image plane.
Compression measure_compression(const StationTruth& truth, const echo::EchoFrame& pressed, const echo::ImagePlane& plane,
                                const LabelImager& labels);
// The same, from the labels already imaged at `pressed` and at unpressed(pressed).
Compression measure_compression(const StationTruth& truth, const echo::EchoFrame& pressed, const echo::ImagePlane& plane,
                                const std::vector<std::uint8_t>& rest_labels, const std::vector<std::uint8_t>& pressed_labels);
// The plane of `pressed` unpressed: the face where the skin was before the press, nothing deformed.
echo::EchoFrame unpressed(const echo::EchoFrame& pressed);

// How far below the vein's lumen at rest a station's report image reaches at least [mm].
inline constexpr double kStationImageMarginMm = 3.0;
// The depth a station's report image is made and measured at [mm]: the trainee's image's at its
// deepest press, made deeper a centimetre at a time (up to the probe's deepest) until the vein's
// lumen at rest (the tissue unpressed, seen from the pressed face: unpressed()) lies
// kStationImageMarginMm above its bottom. A large patient's CFV (far wall 61 mm under the skin)
// pressed less than 11 mm had its rest lumen cut off by a 50 mm image: its area at rest measured
// short, and the trainee's own 70 mm image stood in the report at 50.
double station_image_depth_mm(const StationTruth& truth, const echo::EchoFrame& pressed, double trainee_depth_mm);

class Scorer {
public:
    Scorer(const Scenario& scenario, std::vector<StationTruth> truth);

    void observe(const ExamSample& sample);
    // The trainee's call, for the station examined last (the one reached most recently).
    void call(double time_s, Call c);

    // Index of the station the probe is at now (reached), if any.
    std::optional<std::size_t> current_station() const { return current_; }
    const std::vector<StationTruth>& truth() const { return truth_; }
    // What the scorer knows of a station so far (the trainer's live leg map): reached, its peak
    // force, the trainee's call, and the errors already seen there.
    struct StationProgress {
        bool reached = false;
        double peak_force_N = 0;
        Call call = Call::none;
        bool oblique = false, wrong_vessel = false;
        bool excessive = false;  // the force held past the excessive limit (kExcessiveHoldS)
    };
    StationProgress progress(std::size_t station) const
    {
        const Tracked& st = stations_[station];
        return {st.reached, st.peak_force_N, st.call, st.oblique, st.wrong_vessel, st.excessive()};
    }
    // The station a call would answer now (the one examined last), if any.
    std::optional<std::size_t> last_examined() const { return last_examined_; }
    // The echo frame at each station's deepest press (none: never pressed there).
    const std::optional<echo::EchoFrame>& deepest_frame(std::size_t station) const { return stations_[station].deepest; }
    // The depth of the trainee's image at that press [mm] (ExamSample::image_depth_mm).
    double deepest_image_depth_mm(std::size_t station) const { return stations_[station].deepest_depth_mm; }

    // The report, given each station's compression (none: not measured, e.g. never pressed) and its
    // image's file name relative to the report ("" for none).
    ExamReport finish(const std::vector<std::optional<Compression>>& compression, const std::vector<std::string>& images) const;

private:
    struct Geometry {
        double lateral_mm = 1e9;  // the axis's crossing of the plane from the beam's centre line, along the array
        double along_mm = 1e9;    // the face's foot on the vessel's axis from the station, along it
        double angle_deg = 90;    // the plane's normal from the vessel's direction
        bool crosses = false;     // the axis crosses the plane within the image's depth
    };
    // `down`: the station's own way into the tissue (its ideal probe's beam), along which the face
    // is carried to the vessel to say where along it the probe sits; `depth_mm`: the image's
    static Geometry geometry(const VesselAxis& axis, const Pose& face, const glm::dvec3& down, double depth_mm);

    struct Tracked {
        bool reached = false;
        double reached_at_s = -1;
        double peak_force_N = 0;  // the deepest press: the highest force held kPressHeldS
        double peak_at_s = -1;    // when that held press ended
        // the samples (time, force) of the run at the station now, back to kPressHeldS before the
        // last (empty: not at the station)
        std::vector<std::pair<double, double>> run;
        Geometry at_peak;
        std::optional<echo::EchoFrame> deepest;
        double deepest_depth_mm = kLinearProbe.image_depth_mm;
        bool oblique = false;
        double oblique_at_s = -1, oblique_angle_deg = 0;
        bool wrong_vessel = false;
        double wrong_vessel_at_s = -1;
        // the force above the excessive limit: since when, without a break (-1: not now), and once
        // it stayed there kExcessiveHoldS, from when (-1: never) and for how long at most
        double above_since_s = -1;
        double excessive_at_s = -1, excessive_held_s = 0;
        bool excessive() const { return excessive_at_s >= 0; }
        std::string wrong_vessel_which;
        Call call = Call::none;
        double call_at_s = -1;
    };

    Scenario scenario_;
    std::vector<StationTruth> truth_;
    std::vector<Tracked> stations_;
    std::vector<Geometry> geometries_;  // observe()'s, kept between samples (no allocation a sample)
    std::optional<std::size_t> current_, last_examined_;
    bool have_last_ = false;
    glm::dvec3 last_position_{0.0};
    double path_mm_ = 0, start_s_ = -1, end_s_ = 0;
    double angle_sum_ = 0, angle_max_ = 0;
    long long angle_samples_ = 0;
    std::vector<std::pair<double, double>> force_trace_;
};

}  // namespace echosim::exam

// What an exam found (DESIGN.md §3, "exam report"): per station, what the simulation's truth says
// the trainee did (reached, pressed, collapsed, called), the errors flagged, the motion, and the
// score. The scorer (exam/scorer.hpp) fills it; report.json/html/png (exam/report_writer.hpp) and
// the trainee records (exam/records.hpp) read it. Plain values: no pointers into the session.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace echosim::exam {

enum class Call { none, compressible, not_compressible };
const char* call_name(Call c);  // "none", "compressible", "not-compressible"

enum class ErrorKind {
    skipped_station,     // a station of the protocol never reached
    too_little_pressure, // reached and pressed, but the peak force under the adequate band
    wrong_vessel,        // pressed over the artery or the great saphenous vein instead of the deep vein
    oblique_plane,       // the plane beyond the transverse tolerance while pressing
    excessive_force,     // the peak force above the excessive limit
    mimic_called_clot,   // a lymph node called not compressible
    wrong_call,          // the call disagrees with the truth
};
const char* error_name(ErrorKind e);  // "skipped-station", ...

struct FlaggedError {
    ErrorKind kind = ErrorKind::skipped_station;
    std::string station;  // the station's name ("" for an error of the whole exam)
    double time_s = 0;    // when it happened (simulated) [s]
    std::string detail;   // one line for the trainee: "peak 6.1 N, adequate from 9.0 N"
};

struct StationResult {
    std::string name;
    std::string segment;          // echo::segment_name
    double s_cm = 0;
    bool reached = false;
    double reached_at_s = -1;     // simulated time first reached [s]
    double offset_mm = 0;         // probe centre from the vein's axis at the deepest press [mm]
    double angle_deg = 0;         // plane from transverse at the deepest press [deg]
    double peak_force_N = 0;
    double deepest_press_at_s = -1;
    double lumen_rest_mm2 = 0;    // the vein's lumen in the image plane before the press
    double lumen_pressed_mm2 = 0; // at the deepest press (deformed labels)
    double collapse_ratio = 1.0;  // pressed over rest: 0 = walls met
    double artery_area_ratio = 1.0;  // the artery's area pressed over rest
    bool thrombosed = false;      // the truth: a thrombus in the vein under this station
    Call call = Call::none;
    bool call_correct = false;
    std::string image_png;        // the echographic image at the deepest press, relative to the report
};

struct MotionSummary {
    double duration_s = 0;        // simulated time of the exam
    double path_mm = 0;           // the probe's path length
    double mean_angle_deg = 0;    // from transverse, while in contact
    double max_angle_deg = 0;
};

// The OSAUS items the exam scores (Tolsgaard et al. 2012), each 1..5.
struct OsausItems {
    double systematic_examination = 1;
    double interpretation = 1;
    double decision = 1;
};

struct ExamReport {
    std::string trainee;
    std::string case_id, case_title, protocol;
    std::string started_utc;      // ISO 8601; "" in repeatable (headless, scripted) runs
    std::vector<StationResult> stations;
    std::vector<FlaggedError> errors;
    MotionSummary motion;
    OsausItems osaus;
    double score = 0;             // 0..1
    double pass_mark = 0.8;
    bool passed = false;
    // the diagnosis the exam supports: "DVT excluded" needs every station of an extended exam
    // collapsed; a two-point exam that collapsed both cannot exclude an isolated femoral clot
    std::string conclusion;
    bool dvt_present = false;     // the truth
    // the case's force bands (ScoringBands), drawn on the report's force trace: the adequate band
    // from adequate_force_N up to excessive_force_N [N]; 0: not known, not drawn
    double adequate_force_N = 0;
    double excessive_force_N = 0;
    // where the course's landmarks lie along the deep vein [cm from the inguinal ligament, the
    // deep vein's s] (the phantom's vein course), for the report's leg map to place its stations
    // to scale; 0: not given, the map takes them from the stations' segments
    struct CourseLandmarks {
        double sfj_cm = 0;           // the saphenofemoral junction
        double bifurcation_cm = 0;   // the CFV dividing into FV and DFV
        double hiatus_cm = 0;        // the adductor hiatus: FV into popliteal
        double trifurcation_cm = 0;  // the popliteal vein's end
    } course;
    // the force over time, for the trace: every sample (t [s], force [N])
    std::vector<std::pair<double, double>> force_trace;
};

}  // namespace echosim::exam

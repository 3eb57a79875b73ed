// A case as a file (DESIGN.md §3, "case"): the patient, the anatomy (thrombi per segment, mimics),
// the protocol's stations and the scoring's bands. Immutable once read (as TissueModel is): the
// exam's scorer, the phantom and the lesson read it, nothing writes it. An instructor writes one
// in JSON against assets/cases/scenario.schema.json; `echosim case validate F` checks it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "echo/anatomy.hpp"
#include "echo/echo_frame.hpp"

namespace echosim::exam {

enum class Protocol { two_point, three_point, extended };
const char* protocol_name(Protocol p);  // "two-point", "three-point", "extended"

// Where a station is: on a named landmark of the vein course, or at a distance along a segment.
struct Station {
    std::string name;            // shown to the trainee and in the report: "CFV", "SFJ", "FV 6 cm"
    echo::VeinSegment segment = echo::VeinSegment::cfv;  // the vein compressed there
    double s_cm = 0;             // along that segment's s (echo/anatomy.hpp)
};

// The scoring's bands.
struct ScoringBands {
    double adequate_force_N = 0;   // at least this at the deepest press (set by the fat: a large patient needs more)
    double excessive_force_N = 0;  // above this: excessive force flagged
    double reach_mm = 5.0;         // probe centre within this of the vein's axis, in the image plane
    double transverse_deg = 15.0;  // the plane within this of transverse to the vein
    double collapsed_ratio = 0.1;  // the lumen's area at the deepest press over its rest area at or below: walls met
    double artery_deformed = 0.25; // the artery's area lost beyond this fraction: the artery was pressed too
    double pass_mark = 0.8;        // overall score in 0..1 needed to pass
};

struct Patient {
    double venous_pressure_mmHg = 10.0;
    double heart_rate_bpm = 70.0;
};

using echo::Imaging;  // the image a case is shown with (echo/echo_frame.hpp)
using echo::imaging_name;

struct Scenario {
    std::string id;            // file-name-like, unique among the shipped cases: "healthy", "fv-isolated-acute"
    std::string title;         // one line for the start screen and the report
    std::string description;   // what the instructor wants the trainee to learn (may be empty)
    Patient patient;
    echo::Anatomy anatomy;     // fat, thrombi, mimics
    Protocol protocol = Protocol::extended;
    std::vector<Station> stations;  // in the order the protocol visits them
    ScoringBands bands;
    // how the image is made; unset: as the machine suits (runner::RunnerConfig::imaging)
    std::optional<Imaging> imaging;
};

// The error of a case file: which file, the field's JSON path ("/thrombi/0/extent_cm") and why.
struct ScenarioError : std::runtime_error {
    ScenarioError(const std::filesystem::path& file, const std::string& field, const std::string& why);
    std::filesystem::path file;
    std::string field;
};

// Reads and checks a case file: the schema's types and ranges, unknown fields, and the anatomy
// (segments exist, a thrombus lies within its segment, stations within the course). Throws
// ScenarioError naming the file and the field at fault.
Scenario read_scenario(const std::filesystem::path& file);
Scenario parse_scenario(const std::string& json_text, const std::filesystem::path& file_for_messages);

// The shipped cases (assets/cases/*.json, by id), and one drawn from them by `seed` (--case random).
// A shipped case's file is named by its id (ID.json). shipped_cases() lists them sorted by file name.
std::vector<std::filesystem::path> shipped_cases();
std::filesystem::path shipped_case(const std::string& id);  // throws naming the id and listing the ids
// One of shipped_cases(), drawn by `seed`: the same seed draws the same case; seeds spread evenly
// over the cases (a trainee given a fresh seed cannot tell which case comes).
std::filesystem::path random_case(std::uint64_t seed);

}  // namespace echosim::exam

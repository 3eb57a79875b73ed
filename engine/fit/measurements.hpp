// Force-displacement measurements (paper §3.1) in DESIGN.md's CSV format:
//     point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N
// one row per sample: which of the sample points, which probe (`indenter`: the punctual tip,
// `probe`: the pseudo-probe with a real probe's face), the point on the skin (world LPS mm), the
// outward skin normal there, how deep the probe had pushed [mm] and the force measured [N].
// Lines starting with '#' are comments (provenance); columns may come in any order.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/printable_text.hpp"

namespace echosim::fit {

enum class ProbeKind { indenter, probe };
const char* to_string(ProbeKind kind);

struct Sample {
    int point = 0;
    ProbeKind probe = ProbeKind::indenter;
    glm::dvec3 position{0.0};  // [mm]
    glm::dvec3 normal{0.0};    // outward, unit
    double depth_mm = 0.0;
    double force_N = 0.0;
};

struct MeasurementSet {
    std::vector<Sample> samples;
    std::vector<std::string> comments;  // the '#' lines, without the '#'

    int point_count() const;  // 1 + the largest point index
};

// Thrown for a malformed file; what() names the file, the line and the field.
class MeasurementError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

MeasurementSet read_measurements(const std::filesystem::path& path);
// Written through a temporary file and renamed into place.
void write_measurements(const std::filesystem::path& path, const MeasurementSet& set);

}  // namespace echosim::fit

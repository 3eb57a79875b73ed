// What the echographic image pipeline (DESIGN.md §1: slice ▶ deform ▶ post) takes, on the CPU twin
// and on the GPU alike: the image plane, the scanner's settings, the patient's case, and one frame's
// probe and indentation, which the session makes from one physics snapshot (so the force the
// trainee feels and the image they see come from the same moment).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/image_limits.hpp"
#include "core/pose.hpp"
#include "core/probe_spec.hpp"
#include "echo/phantom.hpp"

namespace echosim::echo {

// The image of a linear probe: `width_mm` along the array, centred on the probe, by `depth_mm`
// along the beam from the face, in columns x rows pixels (not necessarily square).
struct ImagePlane {
    double width_mm = kLinearProbe.face_width_mm;
    double depth_mm = kLinearProbe.image_depth_mm;
    std::uint32_t columns = 400;
    std::uint32_t rows = 500;

    double pixel_x_mm() const { return width_mm / columns; }
    double pixel_y_mm() const { return depth_mm / rows; }
    std::uint64_t pixels() const { return std::uint64_t(columns) * rows; }
};
// The most pixels a side may have, and in all: core/image_limits.hpp.
using echosim::kMaxImageSide;
using echosim::kMaxImagePixels;
// Throws std::invalid_argument naming the field (width, depth, columns, rows) that is out of range.
void check_plane(const ImagePlane& plane);
// The plane of the given size in mm at about `pixel_mm` pixels.
ImagePlane plane_with_pixel(double width_mm, double depth_mm, double pixel_mm);
// Where the image of a probe whose face is at `face` lies: pixel (column, row, 0, 1) to world mm, at
// pixel centres (column c at x = (c + 0.5) pixel_x_mm - width_mm / 2 along the array, row r at
// y = (r + 0.5) pixel_y_mm along the beam); the third column is the elevational axis, of unit
// length (scale it by a slice's thickness).
glm::dmat4 pixel_to_world(const ImagePlane& plane, const Pose& face);

// How the echographic image is made: sliced from the case's reconstructed volume, the slice
// deformed by the pressed tissue (interpolative, paper §6); or synthesised on each frame from the
// case's anatomy where the pressed tissue rests (generative: the B-mode model, echo/bmode.hpp,
// synthesize_live), its speckle attached to the tissue.
enum class Imaging { interpolative, generative };
const char* imaging_name(Imaging imaging);
// "interpolative" or "generative"; throws std::invalid_argument naming the value otherwise.
Imaging parse_imaging(const std::string& name);

// The scanner's controls.
struct ScannerSettings {
    double gain_db = 0.0;
    double dynamic_range_db = 55.0;
    std::array<float, 8> tgc_db{};  // the time-gain sliders, top to bottom [dB]
    double focus_mm = 20.0;         // the transmit focus [mm]
    bool markers = true;            // depth ticks and the focus marker
    // the dB the volume's grey levels span (the dynamic range it was made with: echo::ScanSpec's)
    double volume_dynamic_range_db = 55.0;
};

// The patient: which case, and the pressures and rate the vessels follow.
struct PatientCase {
    Case which = Case::healthy;
    double venous_pressure_mmHg = 10.0;  // supine, at the thigh
    double heart_rate_bpm = 70.0;        // 0: no pulse
};
inline constexpr double kPascalPerMmHg = 133.322;

// Where the heart cycle is at `time_s`: 0 in diastole, rising to 1 at the systolic peak and back
// over the first 35 % of the cycle (the cycle starts at t = 0).
double pulse_at(double time_s, double heart_rate_bpm);

// The skin in one image column: where it was before the probe pressed (y along the beam in the
// pressed probe's frame [mm]: negative above the face) and how far it has moved along the beam.
struct ColumnProfile {
    float skin_y_mm = 0.0f;
    float skin_shift_mm = 0.0f;
};

// One frame's input.
struct EchoFrame {
    Pose face;                            // the probe's face, pressed where it is
    std::vector<ColumnProfile> columns;   // one per image column, or empty: nothing pressed
    double skin_pressure_kpa = 0.0;       // the probe's force over its face [kPa]
    double time_s = 0.0;                  // for the pulse
};

// One image out of the pipeline. `rgba`: what the display shows (grey, alpha 255); the stages'
// outputs on the way, for tests and tools: the deform map (vec2 per entry: source y [mm], gain
// [dB], map_columns x rows entries, echo::deform_columns; empty when nothing pressed), the sliced
// grey level (0..255), and the tissue codes at the pixels (when asked for and the volume has labels).
struct EchoImage {
    std::uint32_t columns = 0, rows = 0;
    std::uint32_t map_columns = 0;
    std::vector<std::uint32_t> rgba;
    std::vector<float> map;  // 2 per entry
    std::vector<float> grey;
    std::vector<std::uint8_t> labels;
};

}  // namespace echosim::echo

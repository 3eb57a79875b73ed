// The linear vascular probe echosim simulates (DESIGN.md §2, "Probe frame"), one source for every
// part that needs its size or its sound: the scene draws its face, the contact presses it, the fit's
// pseudo-probe measures with it, the B-mode synthesis and the image pipeline image with it.
//
// Probe frame: origin at the centre of the transducer face, +x lateral along the array (the image
// width), +y into the tissue along the beam (the image depth), +z elevational = x cross y.
#pragma once

namespace echosim {

struct ProbeSpec {
    double face_width_mm = 40.0;     // the face along the array (probe x); also the image width
    double face_thickness_mm = 10.0; // the face across the array (probe z)
    double image_depth_mm = 50.0;    // how deep the image reaches along the beam (probe y), at the start
    // the scanner's depth control: from the superficial thigh of a slim patient to a large patient's
    // femoral vein (its centre 55 mm under the skin at the groin, its far wall at 61)
    double image_depth_min_mm = 30.0;
    double image_depth_max_mm = 70.0;
    double frequency_mhz = 10.0;     // centre frequency of the transmitted pulse

    // The pressure a force on the probe puts on the skin under its face, spread evenly [kPa]
    constexpr double face_pressure_kpa(double force_N) const { return 1000.0 * force_N / (face_width_mm * face_thickness_mm); }
};

// The 7.5-12 MHz linear vascular probe of the compression exam.
inline constexpr ProbeSpec kLinearProbe{};

}  // namespace echosim

// A tracked sweep of the phantom, as a sonographer's freehand acquisition would give it: transverse
// frames from the groin down the thigh along the patch's middle, at the acquisition rate, with hand
// tremor (a smooth random wander of position and tilt). Each frame's image-to-world transform maps
// pixel (column, row) to world mm, as PLUS's ImageToReference does.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/pose.hpp"
#include "echo/bmode.hpp"
#include "io/plus_sequence.hpp"
#include "scene/leg.hpp"

namespace echosim::echo {

struct SweepOptions {
    int frames = 240;
    float u_from = 0.04f, u_to = 0.96f;  // along the patch (superior to inferior)
    float v = 0.5f;                      // across it
    double frame_rate_hz = 30.0;
    double tremor_mm = 0.3;              // standard deviation of the hand's wander
    double tremor_deg = 1.0;
    std::uint64_t seed = 1;
    ScanSpec spec;
};

struct TrackedSweep {
    io::Sweep sweep;                  // pixels and transforms, ready for a PLUS file
    std::vector<std::uint8_t> labels; // tissue codes, same layout as sweep.pixels
    std::vector<Pose> poses;          // the probe's pose for each frame
};

// Pixel (column, row) of an image taken at `pose` to world mm.
glm::dmat4 image_to_world(const Pose& pose, const ScanSpec& spec);

TrackedSweep make_sweep(const scene::LegModel& leg, const Medium& medium, const SweepOptions& options,
                        const std::function<void(int done, int total)>& progress = {});

}  // namespace echosim::echo

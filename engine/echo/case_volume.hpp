// The volume of a patient's case made from scratch, as a researcher would make it from a real
// exam: the phantom imaged by the B-mode model along a tracked freehand sweep down the thigh, and
// the sweep reconstructed into a voxel map with its tissue labels (DESIGN.md §1, "ultrasound data").
// What `echosim run` shows when the user brings no volume of their own (made once, then cached:
// app/volume_cache.hpp).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "echo/phantom.hpp"
#include "echo/sweep.hpp"
#include "io/nrrd.hpp"
#include "scene/leg.hpp"

namespace echosim::echo {

struct CaseVolume {
    io::Volume volume;  // uint8 grey, LPS
    io::Volume labels;  // uint8 tissue codes on the same grid
};

struct CaseVolumeOptions {
    double voxel_mm = 0.3;
    int frames = 240;       // the sweep's frames (8 s at 30 frames/s)
    double pixel_mm = 0.1;  // the frames' pixels
    // the frames' depth [mm]: the image's 50 mm and the deepest press (25 mm), so a pressed probe
    // still finds tissue at the bottom of its image
    double depth_mm = 75.0;
    LabelVolumeOptions anatomy;  // the phantom voxelised over the frames, as the imager takes it
    // What images the frames from the anatomy's label volume: empty, the CPU twin (CpuSweepImager);
    // the app layer hands the GPU's here when a device is at hand (image/bmode_gpu.hpp).
    std::function<std::unique_ptr<SweepImager>(std::shared_ptr<const io::Volume> labels, const ScanSpec& spec)> imager;
};

// `progress` (may be empty) is told what is being done and the fraction of it done.
CaseVolume make_case_volume(const scene::LegModel& leg, Case which, const CaseVolumeOptions& options = {},
                            const std::function<void(const std::string& stage, double done)>& progress = {});

}  // namespace echosim::echo

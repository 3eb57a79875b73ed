// The volume of a patient's case made from scratch, as a researcher would make it from a real
// exam: the phantom imaged by the B-mode model along a tracked sweep that follows the vein course
// (echo/vein_course.hpp) from above the inguinal ligament down the anterior-medial thigh to the
// adductor canal, then from the posterior-medial skin over the popliteal fossa to below the
// trifurcation, and the frames reconstructed into a voxel map with its tissue labels (DESIGN.md
// §1, "ultrasound data"). What `echosim run` and `echosim exam` show when the user brings no
// volume of their own (made once, then cached: app/volume_source.hpp).
//
// Each frame is transverse to the vein where the probe rests on the skin right above it
// (Phantom::transverse_probe_pose), wider than the probe (width_mm), so a probe slid 12 mm off the
// vein either side or turned a little still finds the volume; the frames are voxelised and imaged
// in chunks (chunk_frames), each chunk's anatomy a label volume of its own (voxelise_frames), so the
// course's L shape never needs one label volume over its whole box. The voxel map is the box of
// all frames turned to hold them with the fewest voxels.
//
// Costs at the defaults (0.4 mm voxels, 1,060 frames 0.5 mm apart of 64 x 95 mm at 0.2 mm pixels):
// a box of about 107 x 115 x 538 mm, 104 M voxels: volume and labels 208 MB, the reconstruction's
// working memory 13 bytes a voxel (1.35 GB) while it is made.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/pose.hpp"
#include "echo/anatomy.hpp"
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
    double voxel_mm = 0.4;
    int frames = 1060;      // the sweep's frames along the whole course (about 0.5 mm apart)
    double pixel_mm = 0.2;  // the frames' pixels
    // the frames' depth [mm]: the deepest image (kLinearProbe.image_depth_max_mm, 70 mm) and the
    // deepest press (session::Session::kMaxPressMm, 25 mm), so a probe pressed in all the way still
    // finds recorded tissue at the bottom of its deepest image
    double depth_mm = 95.0;
    LabelVolumeOptions anatomy;  // the phantom voxelised over the frames, as the imager takes it
    // What images the frames from the anatomy's label volume: empty, the CPU twin (CpuSweepImager);
    // the app layer hands the GPU's here when a device is at hand (image/bmode_gpu.hpp).
    std::function<std::unique_ptr<SweepImager>(std::shared_ptr<const io::Volume> labels, const ScanSpec& spec)> imager;
    // the frames' width [mm]: the probe's face and 12 mm either side
    double width_mm = 64.0;
    int chunk_frames = 96;  // frames voxelised and imaged together
};

// The cheap volume for tests and benchmarks: 0.6 mm voxels from a quarter of the frames at 0.3 mm
// pixels (as the soak's).
CaseVolumeOptions coarse_case_volume_options();

// The sweep's probe poses, `frames` of them along the course: the deep vein from above the
// ligament (kDeepVeinFrom_cm + 0.5) to 1 cm past the adductor hiatus, then the popliteal vein from
// 1 cm above the hiatus to 1 cm past the trifurcation, the frames shared by length. Each is
// Phantom::transverse_probe_pose.
std::vector<Pose> course_sweep_poses(const Phantom& phantom, int frames);

// `progress` (may be empty) is told what is being done and the fraction of it done.
CaseVolume make_case_volume(const scene::LegModel& leg, const Anatomy& anatomy, const CaseVolumeOptions& options = {},
                            const std::function<void(const std::string& stage, double done)>& progress = {});
// A preset case's (anatomy_of), its name in the volumes' "case" key.
CaseVolume make_case_volume(const scene::LegModel& leg, Case which, const CaseVolumeOptions& options = {},
                            const std::function<void(const std::string& stage, double done)>& progress = {});

}  // namespace echosim::echo

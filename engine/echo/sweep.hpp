// A tracked sweep of the phantom, as a sonographer's freehand acquisition would give it: transverse
// frames from the groin down the thigh along the patch's middle, at the acquisition rate, with hand
// tremor (a smooth random wander of position and tilt). Each frame's image-to-world transform maps
// pixel (column, row) to world mm, as PLUS's ImageToReference does.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
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

// The sweep's probe poses: down the patch, with the hand's tremor (seeded by options.seed).
std::vector<Pose> sweep_poses(const scene::LegModel& leg, const SweepOptions& options);

// The sweep imaged with the tissue of each pixel asked of `medium` directly, one frame at a time
// on this thread.
TrackedSweep make_sweep(const scene::LegModel& leg, const Medium& medium, const SweepOptions& options,
                        const std::function<void(int done, int total)>& progress = {});

// What images a sweep's frames from the anatomy as a label volume (voxelise_frames): the CPU twin
// (CpuSweepImager) or the GPU kernels (image/bmode_gpu.hpp), chosen by the caller (the app layer,
// which may see the GPU).
class SweepImager {
public:
    virtual ~SweepImager() = default;
    // Frames per image() call that suit it (a GPU batch; the CPU's threads).
    virtual std::size_t batch_frames() const = 0;
    // Grey pixels and tissue codes of the frames at `poses`, row-major, frame after frame (each
    // columns x rows of the imager's ScanSpec), into `pixels` and `labels`.
    virtual void image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels) = 0;
    // Which backend images: "cpu", or the Vulkan device's name.
    virtual std::string backend() const = 0;
};

// The CPU twin of the kernels, frames in parallel on `threads` threads (0: all cores).
class CpuSweepImager : public SweepImager {
public:
    CpuSweepImager(std::shared_ptr<const io::Volume> labels, const ScanSpec& spec, int threads = 0);
    ~CpuSweepImager() override;
    std::size_t batch_frames() const override;
    void image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels) override;
    std::string backend() const override { return "cpu"; }

private:
    std::shared_ptr<const io::Volume> labels_;
    kernels::BModeParams params_;
    struct Team;
    std::unique_ptr<Team> team_;
};

// The sweep imaged by `imager` (made for options.spec), `imager.batch_frames()` frames at a time.
TrackedSweep make_sweep(const scene::LegModel& leg, SweepImager& imager, const SweepOptions& options,
                        const std::function<void(int done, int total)>& progress = {});

}  // namespace echosim::echo

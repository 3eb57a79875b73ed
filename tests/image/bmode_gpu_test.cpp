// The B-mode kernels (engine/image/bmode_gpu) against their CPU twin (engine/echo/bmode), on
// lavapipe with validation on (the count read after the device is gone): the same frame of the
// phantom from the same label volume, the speckle gates (one body with the twin's:
// tests/echo/bmode_gates.hpp), and a sweep made on the GPU reconstructed against the CPU's.
#include "image/bmode_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "echo/bmode_gates.hpp"
#include "echo/case_volume.hpp"
#include "echo/reconstruct.hpp"
#include "echo/sweep.hpp"
#include "test_gpu.hpp"

namespace echosim::image {
namespace {

using echo::BModeImage;

const scene::LegModel& leg()
{
    static const scene::LegModel model;
    return model;
}

// The GPU's frame at `pose` from `labels`, validation messages counted into `messages`.
BModeImage gpu_frame(const io::Volume& labels, const Pose& pose, const echo::ScanSpec& spec, std::uint32_t& messages)
{
    gpu::Context ctx(test::lavapipe_options());
    const auto counter = ctx.validation_counter();
    BModeImage img;
    {
        gpu::CommandPool pool(ctx);
        BModeGpu bmode(pool, labels, spec);
        img = bmode.synthesize(pose);
    }
    messages = counter->load();
    return img;
}

TEST(BModeGpu, FrameOfThePhantomMatchesTheCpuTwin)
{
    // a small frame over the vessels of the acute case: vessel walls, thrombus, fat septa, muscle
    const echo::Phantom phantom(leg(), echo::Case::dvt_acute);
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    echo::ScanSpec spec;
    spec.width_mm = 16;
    spec.depth_mm = 30;
    const io::Volume labels = echo::voxelise_frames(echo::PhantomMedium(phantom), std::span(&pose, 1), spec);
    const BModeImage cpu = echo::synthesize(labels, pose, spec);
    std::uint32_t messages = 0;
    const BModeImage gpu = gpu_frame(labels, pose, spec, messages);
    EXPECT_EQ(messages, 0u);
    ASSERT_EQ(gpu.pixels.size(), cpu.pixels.size());
    // tolerance: the kernels and the twin run the same float operations in the same order, so the
    // tissue codes agree exactly and the envelope to within the rounding of a few library functions
    // (relative 1e-4 at 99.9 % of pixels); grey within one level (log10 against log2 * log10(2),
    // as the log compression kernel's own test allows), at most 0.5 % of pixels off by that level
    std::size_t off = 0, label_off = 0, envelope_off = 0;
    double mean_difference = 0;
    int worst = 0;
    for (std::size_t k = 0; k < cpu.pixels.size(); ++k) {
        const int d = int(gpu.pixels[k]) - int(cpu.pixels[k]);
        worst = std::max(worst, std::abs(d));
        off += d != 0;
        mean_difference += d;
        label_off += gpu.labels[k] != cpu.labels[k];
        envelope_off += std::abs(gpu.envelope[k] - cpu.envelope[k]) > 1e-4f * std::max(cpu.envelope[k], 1e-3f);
    }
    mean_difference /= double(cpu.pixels.size());
    std::printf("GPU against the CPU twin, %ux%u: grey off at %zu pixels (worst %d levels), mean %+.4f; labels off at %zu; envelope off at %zu\n",
                cpu.width, cpu.height, off, worst, mean_difference, label_off, envelope_off);
    EXPECT_EQ(label_off, 0u);
    EXPECT_LE(worst, 1);
    EXPECT_LE(double(off), 0.005 * double(cpu.pixels.size()));
    EXPECT_LT(std::abs(mean_difference), 0.01);
    EXPECT_LE(double(envelope_off), 0.001 * double(cpu.pixels.size()));
}

TEST(BModeGpu, SpeckleGates)
{
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    const echo::ScanSpec spec = echo::gates::homogeneous_spec(30, 30);
    const io::Volume labels = echo::gates::muscle_volume(pose, spec);
    std::uint32_t messages = 0;
    const BModeImage img = gpu_frame(labels, pose, spec, messages);
    EXPECT_EQ(messages, 0u);
    echo::gates::expect_speckle_gates(img, spec, "GPU");
}

// A sweep's frames reconstructed at 0.3 mm, as echo::make_case_volume does.
echo::CaseVolume reconstruct(const echo::TrackedSweep& sweep)
{
    const echo::SweepBox box = echo::sweep_box(sweep.sweep);
    echo::ReconstructOptions o;
    o.voxel_mm = 0.3;
    echo::Reconstructor r(box.lo - glm::dvec3(0.3), box.hi + glm::dvec3(0.3), o, box.axes);
    const std::size_t bytes = sweep.sweep.frame_bytes();
    for (std::size_t f = 0; f < sweep.sweep.frames.size(); ++f)
        r.insert(std::span(sweep.sweep.frame_pixels(f), bytes), std::span(sweep.labels.data() + f * bytes, bytes), sweep.sweep.width,
                 sweep.sweep.height, sweep.sweep.frames[f].image_to_reference);
    r.fill_holes();
    return {r.volume(), r.labels()};
}

TEST(BModeGpu, SweepReconstructsToTheCpusVolume)
{
    // 24 frames down 12 mm of the healthy thigh, 0.2 mm pixels: imaged by the kernels (in batches of
    // 5, so a partial batch runs too) and by the CPU twin from the same label volume, and by the
    // CPU from the phantom asked at every pixel (the path before the label volume)
    const echo::Phantom phantom(leg(), echo::Case::healthy);
    const echo::PhantomMedium medium(phantom);
    echo::SweepOptions o;
    o.frames = 24;
    o.u_from = 0.45f;
    o.u_to = 0.55f;
    o.spec.pixel_mm = 0.2;
    o.spec.depth_mm = 35;
    const auto labels = std::make_shared<const io::Volume>(echo::voxelise_frames(medium, echo::sweep_poses(leg(), o), o.spec));
    echo::TrackedSweep on_gpu;
    std::uint32_t messages = 0;
    {
        gpu::Context ctx(test::lavapipe_options());
        const auto counter = ctx.validation_counter();
        {
            gpu::CommandPool pool(ctx);
            BModeGpu bmode(pool, *labels, o.spec, 5);
            on_gpu = echo::make_sweep(leg(), bmode, o);
        }
        messages = counter->load();
    }
    EXPECT_EQ(messages, 0u);
    echo::CpuSweepImager twin(labels, o.spec);
    const echo::TrackedSweep on_cpu = echo::make_sweep(leg(), twin, o);
    const echo::TrackedSweep direct = echo::make_sweep(leg(), medium, o);

    const echo::CaseVolume a = reconstruct(on_gpu), b = reconstruct(on_cpu), c = reconstruct(direct);
    ASSERT_EQ(a.volume.data.size(), b.volume.data.size());
    ASSERT_EQ(a.volume.data.size(), c.volume.data.size());
    // against the twin's: the frames' one-level grey differences, averaged by the reconstruction
    double twin_mean = 0;
    int twin_worst = 0;
    std::size_t twin_labels = 0, direct_labels = 0, inside = 0;
    double sa = 0, sc = 0, saa = 0, scc = 0, sac = 0;
    for (std::size_t k = 0; k < a.volume.data.size(); ++k) {
        const int d = std::abs(int(a.volume.data[k]) - int(b.volume.data[k]));
        twin_mean += d;
        twin_worst = std::max(twin_worst, d);
        twin_labels += a.labels.data[k] != b.labels.data[k];
        if (c.labels.data[k] == 0) continue;  // the gel above the skin: no speckle to compare
        ++inside;
        direct_labels += a.labels.data[k] != c.labels.data[k];
        const double x = a.volume.data[k], y = c.volume.data[k];
        sa += x, sc += y, saa += x * x, scc += y * y, sac += x * y;
    }
    twin_mean /= double(a.volume.data.size());
    const double n = double(inside);
    const double ncc = (sac - sa * sc / n) / std::sqrt((saa - sa * sa / n) * (scc - sc * sc / n));
    std::printf("GPU sweep's volume against the CPU twin's: mean |grey difference| %.4f, worst %d, labels off at %zu of %zu voxels; "
                "against the CPU's from the phantom directly: NCC %.3f, labels off at %.2f %% of %zu voxels\n",
                twin_mean, twin_worst, twin_labels, a.volume.data.size(), ncc, 100.0 * double(direct_labels) / n, inside);
    EXPECT_LT(twin_mean, 0.05);
    EXPECT_LE(twin_worst, 1);
    EXPECT_EQ(twin_labels, 0u);
    // the label volume (0.2 mm) against asking the phantom at each 0.2 mm pixel: boundaries move by
    // up to a voxel, the speckle (fixed in the body) is the same
    EXPECT_GT(ncc, 0.9);
    EXPECT_LT(double(direct_labels) / n, 0.03);
}

}  // namespace
}  // namespace echosim::image

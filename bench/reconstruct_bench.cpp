// Suite "reconstruct": freehand reconstruction of a 300-frame sweep of 640 x 480 frames (10 s at
// 30 frames/s, 40 x 30 mm images, down 120 mm of the thigh with hand tremor) at 0.3 mm and 0.1 mm
// voxels: frames inserted per second (trilinear splat, mean compounding), hole-filling time and
// the memory the map needs. Pixel content does not change the cost; the frames carry speckle-like
// noise.
// Rows reconstruct/plus-820x616/...: a PLUS-style recording (PLUS's common frame size, 820 x 616
// pixels of 0.07 mm, 240 frames 0.25 mm apart, written as a .mha sequence) read, resolved with a
// configuration's calibration, gridded by PLUS's rule and pasted at 0.5 mm, nearest neighbour and
// linear, mean compounding, no hole filling (PLUS's defaults): frames per second pasted and for the
// whole command (reading the file included).
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <unistd.h>

#include "io/plus_sequence.hpp"

#include "bench/suites.hpp"
#include "echo/reconstruct.hpp"
#include "echo/sweep.hpp"
#include "scene/leg.hpp"

namespace echosim::bench {
namespace {

struct ReconstructFixture {
    std::uint32_t width = 640, height = 480;
    std::vector<std::uint8_t> pixels;  // one frame, reused
    std::vector<glm::dmat4> transforms;
    ReconstructFixture()
    {
        const scene::LegModel leg;
        echo::ScanSpec spec;
        spec.pixel_mm = spec.width_mm / width;  // the probe's face spans the frame's width
        spec.depth_mm = spec.pixel_mm * height;
        std::mt19937 rng(1);
        std::normal_distribution<double> g(0.0, 1.0);
        double wx = 0, wz = 0;
        for (int f = 0; f < 300; ++f) {
            Pose pose = leg.probe_rest_pose(0.04f + 0.92f * float(f) / 299.0f, 0.5f);
            wx = 0.9 * wx + 0.13 * g(rng), wz = 0.9 * wz + 0.13 * g(rng);
            pose.position += float(wx) * pose.axis_x() + float(wz) * pose.axis_z();
            transforms.push_back(echo::image_to_world(pose, spec));
        }
        pixels.resize(std::size_t(width) * height);
        for (auto& p : pixels) p = std::uint8_t(rng() & 0xff);
    }
};

void reconstruct(benchmark::State& state, const ReconstructFixture& f, double voxel)
{
    using clock = std::chrono::steady_clock;
    double insert_s = 0, fill_s = 0, memory = 0;
    for (auto _ : state) {
        const echo::SweepBox box = echo::sweep_box(f.transforms, f.width, f.height);
        echo::ReconstructOptions o;
        o.voxel_mm = voxel;
        o.memory_budget_bytes = std::uint64_t(16) << 30;
        echo::Reconstructor r(box.lo, box.hi, o, box.axes);
        const auto t0 = clock::now();
        for (const glm::dmat4& m : f.transforms) r.insert(f.pixels, {}, f.width, f.height, m);
        const auto t1 = clock::now();
        r.fill_holes();
        const auto t2 = clock::now();
        insert_s = std::chrono::duration<double>(t1 - t0).count();
        fill_s = std::chrono::duration<double>(t2 - t1).count();
        memory = double(r.memory_bytes()) / (1 << 20);
    }
    state.counters["voxel_mm"] = voxel;
    state.counters["frames_per_s"] = double(f.transforms.size()) / insert_s;
    state.counters["fill_seconds"] = fill_s;
    state.counters["memory_mb"] = memory;
}

// The recording on disk, made once for both rows and removed with the fixture.
struct PlusRecordingFixture {
    static constexpr std::uint32_t width = 820, height = 616;
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("echosim_bench_plus_" + std::to_string(::getpid()) + ".igs.mha");
    glm::dmat4 image_to_probe = glm::translate(glm::dmat4(1.0), glm::dvec3(-28.7, 0, 2)) *
                                glm::scale(glm::dmat4(1.0), glm::dvec3(0.07, 0.07, 1));
    bool written = false;

    void write()
    {
        if (written) return;
        io::Sweep s;
        s.width = width;
        s.height = height;
        std::mt19937 rng(2);
        const int frames = 240;
        s.pixels.resize(std::size_t(width) * height * frames);
        for (auto& p : s.pixels) p = std::uint8_t(rng() & 0xff);
        for (int f = 0; f < frames; ++f) {
            // ProbeToReference per frame; ImageToProbe stays in the "configuration"
            const glm::dmat4 probe_to_reference = glm::translate(glm::dmat4(1.0), glm::dvec3(10, 20, 0.25 * f)) *
                                                  glm::rotate(glm::dmat4(1.0), 0.1 + 0.001 * f, glm::dvec3(0.2, 1, 0.1));
            s.frames.push_back({100 + f / 30.0, probe_to_reference * image_to_probe, true, true});
        }
        io::write_plus_mha(path, s, false);
        written = true;
    }
    ~PlusRecordingFixture()
    {
        std::error_code ec;
        std::filesystem::remove(path, ec);
    }
};

void reconstruct_plus(benchmark::State& state, PlusRecordingFixture& f, echo::Splat splat)
{
    using clock = std::chrono::steady_clock;
    f.write();
    double insert_s = 0, total_s = 0;
    std::size_t frames = 0;
    for (auto _ : state) {
        const auto t0 = clock::now();
        io::PlusRecording recording = io::read_plus_recording(f.path);
        // the file's ImageToReference is the configuration's chain already: resolve through it as
        // reconstruct --config does, so the cost of the repository is in the figure
        const io::Sweep sweep = io::resolve_sweep(f.path, std::move(recording), {}, "Image", "Reference");
        std::vector<glm::dmat4> transforms;
        for (const auto& fr : sweep.frames) transforms.push_back(fr.image_to_reference);
        echo::ReconstructOptions o;
        o.splat = splat;
        o.memory_budget_bytes = std::uint64_t(16) << 30;
        const echo::VoxelGrid grid = echo::plus_grid(transforms, sweep.width, sweep.height, o.clip, glm::dvec3(0.5));
        echo::Reconstructor r(grid, o);
        const auto t1 = clock::now();
        for (std::size_t k = 0; k < sweep.frames.size(); ++k)
            r.insert(echo::FramePixels{{sweep.frame_pixels(k), sweep.frame_bytes()}, sweep.pixel_type, sweep.width, sweep.height}, {},
                     sweep.frames[k].image_to_reference);
        const io::Volume v = r.volume();
        const auto t2 = clock::now();
        benchmark::DoNotOptimize(v.data.data());
        insert_s = std::chrono::duration<double>(t2 - t1).count();
        total_s = std::chrono::duration<double>(t2 - t0).count();
        frames = sweep.frames.size();
    }
    state.counters["frames_per_s"] = double(frames) / insert_s;
    state.counters["frames_per_s_with_reading"] = double(frames) / total_s;
    state.counters["voxel_mm"] = 0.5;
}

struct ReconstructFixtures {
    std::shared_ptr<ReconstructFixture> sweep = std::make_shared<ReconstructFixture>();
    std::shared_ptr<PlusRecordingFixture> plus = std::make_shared<PlusRecordingFixture>();
};

}  // namespace

std::shared_ptr<void> register_reconstruct(const SuiteOptions&)
{
    auto fixtures = std::make_shared<ReconstructFixtures>();
    for (double voxel : {0.3, 0.1})
        benchmark::RegisterBenchmark((std::string("reconstruct/") + (voxel < 0.2 ? "0.1mm" : "0.3mm")).c_str(),
                                     [f = fixtures->sweep.get(), voxel](benchmark::State& s) { reconstruct(s, *f, voxel); })
            ->Unit(benchmark::kSecond)
            ->UseRealTime()
            ->Iterations(1);
    for (const auto& [name, splat] : {std::pair{"nearest", echo::Splat::nearest}, std::pair{"linear", echo::Splat::trilinear}})
        benchmark::RegisterBenchmark((std::string("reconstruct/plus-820x616/0.5mm/") + name).c_str(),
                                     [f = fixtures->plus.get(), splat](benchmark::State& s) { reconstruct_plus(s, *f, splat); })
            ->Unit(benchmark::kSecond)
            ->UseRealTime()
            ->Iterations(1);
    return fixtures;
}

}  // namespace echosim::bench

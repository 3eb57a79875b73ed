// Suite "reconstruct": freehand reconstruction of a 300-frame sweep of 640 x 480 frames (10 s at
// 30 frames/s, 40 x 30 mm images, down 120 mm of the thigh with hand tremor) at 0.3 mm and 0.1 mm
// voxels: frames inserted per second (trilinear splat, mean compounding), hole-filling time and
// the memory the map needs. Pixel content does not change the cost; the frames carry speckle-like
// noise.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>

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

}  // namespace

std::shared_ptr<void> register_reconstruct(const SuiteOptions&)
{
    auto fixture = std::make_shared<ReconstructFixture>();
    for (double voxel : {0.3, 0.1})
        benchmark::RegisterBenchmark((std::string("reconstruct/") + (voxel < 0.2 ? "0.1mm" : "0.3mm")).c_str(),
                                     [f = fixture.get(), voxel](benchmark::State& s) { reconstruct(s, *f, voxel); })
            ->Unit(benchmark::kSecond)
            ->UseRealTime()
            ->Iterations(1);
    return fixture;
}

}  // namespace echosim::bench

// Suite "bmode": B-mode synthesis of sweep frames (issue 33) in frames per second, at 400x500,
// 512x512 and 1024x1024 pixels of 0.1 mm (the probe's 40 x 50 mm image, and square ones 51 and
// 102 mm across), through the acute-DVT phantom voxelised over the frames (echo::voxelise_frames),
// on the CPU twin (all cores), on lavapipe, and on a GPU when one is present. Each iteration images
// one batch of frames down the thigh, as `echosim phantom` does: for the GPU one submit of the three
// passes over the batch, waited for, the grey levels and tissue codes copied out. Rows: width,
// height, backend, mode, fps.
//
// Mode "sweep": as above. Modes "live" and "interpolative": one frame of the echographic image
// (image::EchoImageGpu, recorded and waited for) pressed 5 mm over the femoral vessels, the deform
// stage running each frame: "live" synthesises it from the labels where the pressed tissue rests
// (generative imaging), "interpolative" slices the volume where the same map says (the slice's cost
// does not depend on the grey levels, which are blank here). Labels voxelised at 0.2 mm over the
// frame from 10 mm above the face. Their rows also say where the GPU's time goes, stage by stage
// (counters ms_<stage>: stage_breakdown).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/suites.hpp"
#include "echo/sweep.hpp"
#include "gpu/command_pool.hpp"
#include "image/bmode_gpu.hpp"
#include "image/echo_image_gpu.hpp"
#include "scene/leg.hpp"

namespace echosim::bench {
namespace {

struct BmodeScene {
    echo::ScanSpec spec;
    std::vector<Pose> poses;
    std::shared_ptr<const io::Volume> labels;
};

// A Vulkan device (on first use of its rows).
struct Device {
    std::string name;  // "lavapipe" or "gpu"
    gpu::Context ctx;
    Device(std::string n, const gpu::ContextOptions& o) : name(std::move(n)), ctx(o) {}
};

struct LiveScene {
    echo::ImagePlane plane;
    io::Volume grey, labels;
    echo::EchoFrame frame;
};

struct BmodeFixture {
    scene::LegModel leg;
    std::unique_ptr<echo::Phantom> phantom;
    std::map<std::uint32_t, BmodeScene> scenes;  // by width
    std::map<std::uint32_t, LiveScene> live_scenes;  // by width
    std::unique_ptr<Device> lavapipe, gpu;

    const LiveScene& live_scene(std::uint32_t width, std::uint32_t height)
    {
        auto it = live_scenes.find(width);
        if (it != live_scenes.end()) return it->second;
        if (!phantom) phantom = std::make_unique<echo::Phantom>(leg, echo::Case::dvt_acute);
        constexpr double kPressMm = 5, kAboveMm = 10;
        LiveScene s;
        s.plane = echo::ImagePlane{width * 0.1, height * 0.1, width, height};
        const Pose rest = leg.probe_rest_pose(0.5f, 0.5f);
        echo::ScanSpec spec;
        spec.width_mm = s.plane.width_mm;
        spec.depth_mm = s.plane.depth_mm + kAboveMm;
        const Pose above = pressed_along_beam(rest, -kAboveMm);
        s.labels = echo::voxelise_frames(echo::PhantomMedium(*phantom), std::span(&above, 1), spec);
        s.grey = io::make_volume(s.labels.size, io::VoxelType::uint8);
        s.grey.directions = s.labels.directions;
        s.grey.origin = s.labels.origin;
        s.frame.face = pressed_along_beam(rest, kPressMm);
        s.frame.columns.assign(width, echo::ColumnProfile{float(-kPressMm), float(kPressMm)});
        s.frame.skin_pressure_kpa = 10;
        return live_scenes.emplace(width, std::move(s)).first->second;
    }

    const BmodeScene& scene(std::uint32_t width, std::uint32_t height)
    {
        auto it = scenes.find(width);
        if (it != scenes.end()) return it->second;
        if (!phantom) phantom = std::make_unique<echo::Phantom>(leg, echo::Case::dvt_acute);
        BmodeScene s;
        echo::SweepOptions o;
        o.frames = 64;  // 6 mm of thigh
        o.u_from = 0.47f;
        o.u_to = 0.53f;
        o.spec.width_mm = width * o.spec.pixel_mm;
        o.spec.depth_mm = height * o.spec.pixel_mm;
        s.spec = o.spec;
        s.poses = echo::sweep_poses(leg, o);
        s.labels = std::make_shared<const io::Volume>(echo::voxelise_frames(echo::PhantomMedium(*phantom), s.poses, s.spec));
        return scenes.emplace(width, std::move(s)).first->second;
    }
};

void frames(benchmark::State& state, const BmodeScene& s, echo::SweepImager& imager, const std::string& backend)
{
    const std::size_t n = std::min(imager.batch_frames(), s.poses.size()), bytes = std::size_t(s.spec.columns()) * s.spec.rows();
    std::vector<std::uint8_t> pixels(n * bytes), labels(n * bytes);
    std::size_t at = 0;
    const auto batch = [&] {
        // successive batches down the frames, as a sweep goes
        if (at + n > s.poses.size()) at = 0;
        imager.image(std::span(s.poses).subspan(at, n), pixels.data(), labels.data());
        at += n;
    };
    batch();  // warm-up: the first dispatch of each kernel
    for (auto _ : state) batch();
    state.counters["width"] = s.spec.columns();
    state.counters["height"] = s.spec.rows();
    state.counters["batch"] = double(n);
    state.counters["fps"] = benchmark::Counter(double(state.iterations() * n), benchmark::Counter::kIsRate);
    state.SetLabel("backend=" + backend + " mode=sweep");
}

// Where a frame's GPU time goes: after the timed frames, kTimedFrames more with timestamps between
// the pipeline's stages (gpu/stage_timer.hpp), each stage's median as a counter "ms_<stage>"
// ("ms_solve", "ms_live_scatter", ...) and their sum as "ms_stages" (the GPU's share of a frame;
// the rest of 1/fps is recording, submission and the wait).
template <class OneFrame>
void stage_breakdown(benchmark::State& state, const gpu::Context& ctx, image::EchoImageGpu& pipeline, const OneFrame& one)
{
    constexpr int kTimedFrames = 31;
    try {
        pipeline.enable_stage_timing(ctx);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim bench bmode: no stage times: %s\n", e.what());
        return;
    }
    std::map<std::string, std::vector<double>> times;
    for (int i = 0; i < kTimedFrames; ++i) {
        one();
        for (const auto& [name, ms] : pipeline.stage_times(0)) times[name].push_back(ms);
    }
    double sum = 0;
    for (auto& [name, ms] : times) {
        std::sort(ms.begin(), ms.end());
        const double median = ms[ms.size() / 2];
        std::string key = name.substr(name.find(": ") == std::string::npos ? 0 : name.find(": ") + 2);
        for (char& ch : key)
            if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
        state.counters["ms_" + key] = median;
        sum += median;
    }
    state.counters["ms_stages"] = sum;
}

// Frames of the echographic image, each recorded and waited for, the heart's phase moving on.
void live_frames(benchmark::State& state, Device& d, const LiveScene& s, echo::Imaging imaging)
{
    gpu::CommandPool pool(d.ctx);  // this thread's
    const bool generative = imaging == echo::Imaging::generative;
    const auto volume = std::make_shared<const image::EchoVolumeGpu>(pool, s.grey, &s.labels, image::GreyLayout::best,
                                                                    generative ? image::LabelTexels::make : image::LabelTexels::none);
    image::EchoImageGpu pipeline(d.ctx, volume, s.plane, echo::PatientCase{}, image::DeformReads::best, imaging);
    echo::EchoFrame frame = s.frame;
    const auto one = [&] {
        frame.time_s += 1.0 / 60;
        pool.submit_and_wait([&](VkCommandBuffer cmd) { pipeline.record(cmd, 0, frame, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL); });
    };
    one();  // warm-up
    for (auto _ : state) one();
    stage_breakdown(state, d.ctx, pipeline, one);
    state.counters["width"] = s.plane.columns;
    state.counters["height"] = s.plane.rows;
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.SetLabel("backend=" + (d.name == "gpu" ? d.ctx.device_name() : d.name) + " mode=" + (generative ? "live" : "interpolative"));
}

std::unique_ptr<Device> open_device(const char* name, const gpu::ContextOptions& o)
{
    try {
        return std::make_unique<Device>(name, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim bench bmode: no %s rows: %s\n", name, e.what());
        return nullptr;
    }
}

}  // namespace

std::shared_ptr<void> register_bmode(const SuiteOptions& options)
{
    auto fixture = std::make_shared<BmodeFixture>();
    gpu::ContextOptions cpu_device = options.gpu;
    cpu_device.gpu = "cpu";
    fixture->lavapipe = open_device("lavapipe", cpu_device);
    // the GPU: the one --gpu names, or the best; none when that is the CPU implementation
    if (options.gpu.gpu != "cpu" && options.gpu.gpu != "lavapipe" && options.gpu.gpu != "llvmpipe") {
        fixture->gpu = open_device("gpu", options.gpu);
        if (fixture->gpu && fixture->gpu->ctx.device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU) fixture->gpu.reset();
    }
    BmodeFixture* f = fixture.get();
    const auto add = [&](const std::string& name, auto&& body) {
        benchmark::RegisterBenchmark(name.c_str(), std::forward<decltype(body)>(body))
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(options.min_time_s);
    };
    for (const auto& [w, h] : {std::pair{400u, 500u}, std::pair{512u, 512u}, std::pair{1024u, 1024u}}) {
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        for (Device* d : {f->lavapipe.get(), f->gpu.get()})
            if (d)
                add("bmode/" + d->name + "/" + size, [f, d, w = w, h = h](benchmark::State& s) {
                    const BmodeScene& scene = f->scene(w, h);
                    gpu::CommandPool pool(d->ctx);  // this thread's
                    image::BModeGpu imager(pool, *scene.labels, scene.spec);
                    frames(s, scene, imager, d->name == "gpu" ? d->ctx.device_name() : d->name);
                });
        for (Device* d : {f->lavapipe.get(), f->gpu.get()})
            if (d)
                for (const echo::Imaging imaging : {echo::Imaging::generative, echo::Imaging::interpolative})
                    add("bmode/" + d->name + "/" + size + "/" + (imaging == echo::Imaging::generative ? "live" : "interpolative"),
                        [f, d, w = w, h = h, imaging](benchmark::State& s) { live_frames(s, *d, f->live_scene(w, h), imaging); });
        add("bmode/cpu/" + size, [f, w = w, h = h](benchmark::State& s) {
            const BmodeScene& scene = f->scene(w, h);
            echo::CpuSweepImager imager(scene.labels, scene.spec);
            frames(s, scene, imager, "cpu");
        });
    }
    return fixture;
}

}  // namespace echosim::bench

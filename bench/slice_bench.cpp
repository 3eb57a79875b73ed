// Suite "slice": the echographic image pipeline (deform ▶ slice ▶ post) of a pressed frame, in
// frames per second, at 512², 1024² and 2048² pixels through the thigh phantom's volumes at 0.3 mm
// and 0.1 mm voxels (bench/slice_scene.hpp), on lavapipe, on the CPU twin, and on a GPU when one is
// present. A GPU frame is recorded, submitted and waited for, with nothing read back: what a live
// frame costs. The "slice-only" rows time the slice kernel alone (the pressed frame's warped
// sampling), the "deform-only" rows the deform stage's dispatches alone, so the rest of the
// frame's cost is post and the copy into the displayed image.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <optional>
#include <string>

#include "bench/slice_scene.hpp"
#include "bench/suites.hpp"
#include "echo/echo_image_cpu.hpp"
#include "image/echo_image_gpu.hpp"

namespace echosim::bench {
namespace {

// A Vulkan device and the two volumes uploaded to it (on first use).
struct GpuBackend {
    std::string name;  // "lavapipe" or "gpu"
    gpu::Context ctx;
    std::array<std::shared_ptr<const image::EchoVolumeGpu>, 2> volumes;  // 0.3 mm, 0.1 mm; before ctx goes
    GpuBackend(std::string n, const gpu::ContextOptions& o) : name(std::move(n)), ctx(o) {}
};

// Everything the rows share, made on first use, so a --filter that picks a few rows pays only for
// what they need. The rows run one after the other on the harness's thread.
struct SliceFixture {
    std::optional<SliceVolume> coarse, fine;
    std::map<std::uint32_t, echo::EchoFrame> frames;  // by side [pixels]
    std::unique_ptr<GpuBackend> lavapipe, gpu;

    const SliceVolume& volume(int which)
    {
        if (!coarse) coarse = make_coarse_volume();
        if (which == 1 && !fine) fine = make_fine_volume(*coarse);
        return which == 0 ? *coarse : *fine;
    }
    const echo::EchoFrame& frame(const echo::ImagePlane& plane)
    {
        auto it = frames.find(plane.columns);
        if (it == frames.end()) it = frames.emplace(plane.columns, pressed_frame(plane)).first;
        return it->second;
    }
    std::shared_ptr<const image::EchoVolumeGpu> uploaded(GpuBackend& b, int which)
    {
        auto& v = b.volumes[std::size_t(which)];
        if (!v) {
            const SliceVolume& host = volume(which);
            gpu::CommandPool pool(b.ctx);
            v = std::make_shared<const image::EchoVolumeGpu>(pool, host.grey, &host.labels);
        }
        return v;
    }
};

constexpr const char* kVoxelNames[2] = {"0.3mm", "0.1mm"};

echo::ImagePlane plane_of(std::uint32_t side)
{
    echo::ImagePlane p;  // the probe's 40 x 50 mm
    p.columns = p.rows = side;
    return p;
}

void report(benchmark::State& state, std::uint32_t side, int which, const std::string& backend, const char* stages)
{
    state.counters["width"] = side;
    state.counters["height"] = side;
    state.counters["voxel_mm"] = which == 0 ? 0.3 : 0.1;
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.SetLabel("backend=" + backend + " stages=" + stages);
}

void frames_gpu(benchmark::State& state, SliceFixture& f, GpuBackend& b, std::uint32_t side, int which, image::Stages stages)
{
    const echo::ImagePlane plane = plane_of(side);
    const echo::EchoFrame& frame = f.frame(plane);
    image::EchoImageGpu pipeline(b.ctx, f.uploaded(b, which), plane, echo::PatientCase{});
    gpu::CommandPool pool(b.ctx);  // this thread's
    const auto one = [&](image::Stages s) {
        pool.submit_and_wait([&](VkCommandBuffer cmd) { pipeline.record(cmd, 0, frame, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, s); });
    };
    // warm-up: a whole frame, which also leaves slot 0 the deform map the slice-only rows sample,
    // and one of the frames timed (its kernel variant is made at its first use)
    one(image::Stages::all);
    one(stages);
    for (auto _ : state) one(stages);
    const char* name = stages == image::Stages::all ? "all" : stages == image::Stages::slice_only ? "slice-only" : "deform-only";
    report(state, side, which, b.name, name);
}

void frames_cpu(benchmark::State& state, SliceFixture& f, std::uint32_t side, int which)
{
    const echo::ImagePlane plane = plane_of(side);
    const echo::EchoFrame& frame = f.frame(plane);
    const SliceVolume& v = f.volume(which);
    const echo::ScannerSettings scanner;
    for (auto _ : state)
        benchmark::DoNotOptimize(echo::render_echo_cpu(v.grey, &v.labels, plane, frame, scanner, echo::PatientCase{}));
    report(state, side, which, "cpu", "all");
}

std::unique_ptr<GpuBackend> open_backend(const char* name, const gpu::ContextOptions& o)
{
    try {
        return std::make_unique<GpuBackend>(name, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim bench slice: no %s rows: %s\n", name, e.what());
        return nullptr;
    }
}

}  // namespace

std::shared_ptr<void> register_slice(const SuiteOptions& options)
{
    auto fixture = std::make_shared<SliceFixture>();
    gpu::ContextOptions cpu_device = options.gpu;
    cpu_device.gpu = "cpu";
    fixture->lavapipe = open_backend("lavapipe", cpu_device);
    // the GPU: the one --gpu names, or the best; none when that is the CPU implementation
    if (options.gpu.gpu != "cpu" && options.gpu.gpu != "lavapipe" && options.gpu.gpu != "llvmpipe") {
        fixture->gpu = open_backend("gpu", options.gpu);
        if (fixture->gpu && fixture->gpu->ctx.device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU) fixture->gpu.reset();
    }

    SliceFixture* f = fixture.get();
    const auto add = [&](const std::string& name, auto&& body, double min_time_s) {
        benchmark::RegisterBenchmark(name.c_str(), std::forward<decltype(body)>(body))
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(min_time_s);
    };
    // the CPU twin takes about a second for a 2048² frame: a shorter minimum keeps the suite short
    const double cpu_min_time_s = std::min(options.min_time_s, 0.5);
    for (std::uint32_t side : {512u, 1024u, 2048u})
        for (int which : {0, 1}) {
            const std::string size = std::to_string(side) + "x" + std::to_string(side) + "/" + kVoxelNames[which];
            for (GpuBackend* b : {f->lavapipe.get(), f->gpu.get()})
                if (b)
                    add("slice/" + b->name + "/" + size,
                        [f, b, side, which](benchmark::State& s) { frames_gpu(s, *f, *b, side, which, image::Stages::all); }, options.min_time_s);
            add("slice/cpu/" + size, [f, side, which](benchmark::State& s) { frames_cpu(s, *f, side, which); }, cpu_min_time_s);
        }
    for (int which : {0, 1})
        for (GpuBackend* b : {f->lavapipe.get(), f->gpu.get()})
            if (b)
                add(std::string("slice-only/") + b->name + "/1024x1024/" + kVoxelNames[which],
                    [f, b, which](benchmark::State& s) { frames_gpu(s, *f, *b, 1024, which, image::Stages::slice_only); }, options.min_time_s);
    for (int which : {0, 1})
        for (GpuBackend* b : {f->lavapipe.get(), f->gpu.get()})
            if (b)
                add(std::string("deform-only/") + b->name + "/1024x1024/" + kVoxelNames[which],
                    [f, b, which](benchmark::State& s) { frames_gpu(s, *f, *b, 1024, which, image::Stages::deform_only); },
                    options.min_time_s);
    return fixture;
}

}  // namespace echosim::bench

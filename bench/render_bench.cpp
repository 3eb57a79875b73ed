// Suite "render": one headless frame of the default scene (leg, patch, probe) at 1920x1080 and
// 3840x2160, drawn only, and drawn and read back to host memory (what `echosim render` and the
// exam recorder pay).
#include <benchmark/benchmark.h>

#include "app/default_scene.hpp"
#include "bench/suites.hpp"
#include "gpu/offscreen.hpp"
#include "render/scene_pass.hpp"

namespace echosim::bench {
namespace {

struct RenderFixture {
    gpu::Context ctx;
    app::DefaultScene scene;
    explicit RenderFixture(const gpu::ContextOptions& o) : ctx(o) {}
};

void render_frame(benchmark::State& state, RenderFixture& f, std::uint32_t width, std::uint32_t height, bool readback)
{
    gpu::CommandPool commands(f.ctx);  // this thread's
    gpu::OffscreenPresenter presenter(commands, {width, height});
    render::ScenePass scene_pass(f.ctx, commands, presenter.format(), f.scene.meshes());
    scene_pass.set_view(f.scene.frame_view());
    const gpu::FramePasses passes{&scene_pass};
    io::RgbaImage image;
    // warm-up, one frame per slot: first-use costs (each slot's depth buffer) stay out
    for (int slot = 0; slot < gpu::kFramesInFlight; ++slot) presenter.render(passes, readback ? &image : nullptr);
    for (auto _ : state) presenter.render(passes, readback ? &image : nullptr);
    state.counters["width"] = width;
    state.counters["height"] = height;
    state.counters["readback"] = readback ? 1 : 0;
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

std::shared_ptr<void> register_render(const SuiteOptions& options)
{
    auto fixture = std::make_shared<RenderFixture>(options.gpu);
    for (auto [w, h] : {std::pair{1920u, 1080u}, std::pair{3840u, 2160u}})
        for (bool readback : {false, true}) {
            const std::string name = "render/" + std::to_string(w) + "x" + std::to_string(h) + (readback ? "/readback" : "/draw");
            benchmark::RegisterBenchmark(name.c_str(), [f = fixture.get(), w, h, readback](benchmark::State& s) {
                render_frame(s, *f, w, h, readback);
            })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(options.min_time_s);
        }
    return fixture;
}

}  // namespace echosim::bench

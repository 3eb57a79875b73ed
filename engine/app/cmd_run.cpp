#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include <GLFW/glfw3.h>

#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/exercise_script.hpp"
#include "app/gpu_args.hpp"
#include "app/window_input.hpp"
#include "gpu/window.hpp"
#include "render/scene_pass.hpp"

namespace echosim::app {
namespace {

void apply_to_window(const RunInput& in, gpu::Window& window)
{
    if (in.resize) glfwSetWindowSize(window.handle(), in.resize->x, in.resize->y);
    if (in.minimise) glfwIconifyWindow(window.handle());
    if (in.restore) glfwRestoreWindow(window.handle());
    if (in.fullscreen) window.set_fullscreen(*in.fullscreen);
    if (in.toggle_fullscreen) window.set_fullscreen(!window.fullscreen());
}

}  // namespace

int run_window(const RunArgs& args)
{
    const gpu::DisplayProbe display = gpu::probe_display();
    if (!display.available) {
        std::fprintf(stderr,
                     "echosim run: %s.\n"
                     "  The simulator needs a display for its window. Without one, render headless:\n"
                     "    echosim render --out frame.png\n",
                     display.reason.c_str());
        return kExitFailure;
    }
    if (args.width < 64 || args.height < 64 || args.width > 7680 || args.height > 4320) {
        std::fprintf(stderr, "echosim run: --width/--height %dx%d outside 64x64..7680x4320\n", args.width, args.height);
        return kExitBadInput;
    }

    gpu::Window window({args.width, args.height, args.fullscreen, "echosim - compression ultrasound of the thigh"});
    gpu::ContextOptions options = context_options(args.gpu);
    options.instance_extensions = gpu::Window::required_instance_extensions();
    options.can_present = &gpu::Window::can_present;
    int presented = 0;
    std::uint32_t swapchains = 0;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(options);
        messages = ctx.validation_counter();
        // the tissue runs in its own thread at 1 kHz; the window sends the probe and draws the
        // latest surface the physics published
        DefaultScene scene({.clock = session::Clock::real_time});
        gpu::CommandPool commands(ctx);  // this (the main) thread's
        gpu::WindowPresenter presenter(commands, window);
        render::ScenePass scene_pass(ctx, commands, presenter.format(), scene.meshes());
        const gpu::FramePasses passes{&scene_pass};
        std::printf("echosim run: %s, %ux%u; left-drag orbits, wheel zooms; right-drag or arrows slide the probe, "
                    "W/S or Shift+wheel press it in and out; F11 fullscreen, Esc quits\n",
                    ctx.device_name().c_str(), presenter.extent().width, presenter.extent().height);

        std::unique_ptr<InputSource> input;
        if (args.exercise)
            input = std::make_unique<ExerciseScript>(glm::ivec2(args.width, args.height));
        else
            input = std::make_unique<WindowInput>(window);
        float u = 0.5f, v = 0.5f;  // the probe on the patch
        double press = 0;          // [mm] into the skin
        double last_title = -1;
        auto last = std::chrono::steady_clock::now();
        while (!window.should_close() && (args.frames == 0 || presented < args.frames)) {
            glfwPollEvents();
            const auto now = std::chrono::steady_clock::now();
            // a frame's time as the probe's speed sees it: a stall (a dragged window) is no leap
            const float dt = std::clamp(std::chrono::duration<float>(now - last).count(), 1e-4f, 0.1f);
            last = now;

            const RunInput in = input->poll(dt);
            if (in.quit) break;
            apply_to_window(in, window);
            scene.camera.orbit(in.orbit_yaw, in.orbit_pitch);
            scene.camera.zoom(in.zoom);
            u = std::clamp(u + in.slide_u, 0.0f, 1.0f);
            v = std::clamp(v + in.slide_v, 0.0f, 1.0f);
            press = std::clamp(in.press_mm.value_or(press + in.press_change_mm), 0.0, 25.0);
            scene.session.place_probe_on_patch(u, v, press);
            scene.session.advance(dt);

            scene_pass.set_view(scene.frame_view());
            const session::SessionView& state = scene.session.view();
            if (scene.session.time() - last_title > 0.2) {
                char title[160];
                std::snprintf(title, sizeof title, "echosim - probe %.1f mm in, %.1f N", state.press_mm, state.probe_force_N);
                glfwSetWindowTitle(window.handle(), title);
                last_title = scene.session.time();
            }
            if (presenter.draw(passes))
                ++presented;
            else
                glfwWaitEventsTimeout(0.05);  // minimised: do not spin
        }
        swapchains = presenter.swapchain_generation();
        scene.session.stop();
        const physics::RunnerStats st = scene.session.physics_stats();
        std::printf("echosim run: physics stepped %lld times (%lld late), last probe force %.2f N\n", static_cast<long long>(st.steps),
                    static_cast<long long>(st.overruns), scene.session.view().probe_force_N);
    }
    std::printf("echosim run: presented %d frames, swapchain created %u times\n", presented, swapchains);
    const std::uint32_t n = messages->load();
    if (n > 0) {
        std::fprintf(stderr, "echosim run: Vulkan validation reported %u message(s)\n", n);
        return kExitValidation;
    }
    return kExitOk;
}

}  // namespace echosim::app

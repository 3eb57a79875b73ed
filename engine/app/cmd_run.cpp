#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <GLFW/glfw3.h>

#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/patch_deformer.hpp"
#include "app/simulation.hpp"
#include "app/gpu_args.hpp"
#include "gpu/window.hpp"
#include "render/scene_pass.hpp"

namespace echosim::app {
namespace {

// What the mouse and keyboard did since the last frame; filled by GLFW callbacks on the main thread.
struct Controls {
    bool dragging = false;        // left button: orbit the camera
    bool moving_probe = false;    // right button: slide the probe over the patch
    double last_x = 0, last_y = 0;
    double d_x = 0, d_y = 0;      // camera drag [px]
    double probe_x = 0, probe_y = 0;  // probe drag [px]
    double scroll = 0;            // zoom, or with Shift the probe's press
    bool shift = false;
    bool toggle_fullscreen = false;
};

Controls& controls_of(GLFWwindow* w) { return *static_cast<Controls*>(glfwGetWindowUserPointer(w)); }

void install_callbacks(GLFWwindow* w, Controls* c)
{
    glfwSetWindowUserPointer(w, c);
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
        Controls& k = controls_of(win);
        if (button == GLFW_MOUSE_BUTTON_LEFT) k.dragging = action == GLFW_PRESS;
        if (button == GLFW_MOUSE_BUTTON_RIGHT) k.moving_probe = action == GLFW_PRESS;
        glfwGetCursorPos(win, &k.last_x, &k.last_y);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
        Controls& k = controls_of(win);
        if (k.dragging) k.d_x += x - k.last_x, k.d_y += y - k.last_y;
        if (k.moving_probe) k.probe_x += x - k.last_x, k.probe_y += y - k.last_y;
        k.last_x = x;
        k.last_y = y;
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
        Controls& k = controls_of(win);
        k.shift = glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        k.scroll += dy;
    });
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
        if (action != GLFW_PRESS) return;
        if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(win, GLFW_TRUE);
        if (key == GLFW_KEY_F11 || (key == GLFW_KEY_F && !controls_of(win).dragging)) controls_of(win).toggle_fullscreen = true;
    });
}

// The smoke test's script: resize, minimise, restore, go fullscreen and back, at fixed frames.
void exercise(gpu::Window& window, int frame, int width, int height)
{
    switch (frame) {
    case 10: glfwSetWindowSize(window.handle(), std::max(width / 2, 64), std::max(height / 2, 64)); break;
    case 20: glfwIconifyWindow(window.handle()); break;
    case 24: glfwRestoreWindow(window.handle()); break;
    case 30: window.set_fullscreen(true); break;
    case 40: window.set_fullscreen(false); break;
    case 50: glfwSetWindowSize(window.handle(), width + 37, height + 21); break;
    default: break;
    }
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
        DefaultScene scene;
        gpu::WindowPresenter presenter(ctx, window);
        gpu::CommandPool commands(ctx);  // this (the main) thread's
        render::ScenePass scene_pass(ctx, commands, presenter.format(), scene.meshes());
        const gpu::FramePasses passes{&scene_pass};
        // the tissue runs in its own thread at 1 kHz; the window sends probe commands and draws
        // the latest surface it published
        const tissue::TissueModel model = load_simulation_model(scene.leg);
        const PatchDeformer deformer(scene.leg, model);
        physics::PhysicsRunner physics(model, physics::PhysicsOptions{});
        physics.start();
        std::printf("echosim run: %s, %ux%u; left-drag orbits, wheel zooms; right-drag or arrows slide the probe, "
                    "W/S or Shift+wheel press it in and out; F11 fullscreen, Esc quits\n",
                    ctx.device_name().c_str(), presenter.extent().width, presenter.extent().height);

        Controls controls;
        install_callbacks(window.handle(), &controls);
        float u = 0.5f, v = 0.5f;  // probe position on the patch
        double press = 0;          // [mm] into the skin
        double last_title = 0, elapsed = 0;
        auto last = std::chrono::steady_clock::now();
        int loop = 0;
        while (!window.should_close() && (args.frames == 0 || presented < args.frames)) {
            if (args.exercise) exercise(window, loop, args.width, args.height);
            ++loop;
            glfwPollEvents();
            const auto now = std::chrono::steady_clock::now();
            const float dt = std::min(0.1f, std::chrono::duration<float>(now - last).count());
            last = now;

            scene.camera.orbit(float(controls.d_x) * -0.005f, float(controls.d_y) * 0.005f);
            // the wheel zooms; with Shift it presses the probe in and out, 1 mm a notch
            double press_scroll = 0;
            if (controls.shift)
                press_scroll = controls.scroll;
            else
                scene.camera.zoom(float(std::pow(0.9, controls.scroll)));
            controls.d_x = controls.d_y = controls.scroll = 0;
            if (controls.toggle_fullscreen) window.set_fullscreen(!window.fullscreen());
            controls.toggle_fullscreen = false;

            // arrows slide the probe over the patch: 0.4 of the patch a second
            GLFWwindow* w = window.handle();
            const float step = 0.4f * dt;
            u += step * float((glfwGetKey(w, GLFW_KEY_DOWN) == GLFW_PRESS) - (glfwGetKey(w, GLFW_KEY_UP) == GLFW_PRESS));
            v += step * float((glfwGetKey(w, GLFW_KEY_RIGHT) == GLFW_PRESS) - (glfwGetKey(w, GLFW_KEY_LEFT) == GLFW_PRESS));
            // right-drag: down the screen moves the probe down the thigh, across moves it around
            u += 0.002f * float(controls.probe_y);
            v += 0.002f * float(controls.probe_x);
            controls.probe_x = controls.probe_y = 0;
            u = std::clamp(u, 0.0f, 1.0f);
            v = std::clamp(v, 0.0f, 1.0f);
            // W/S press the probe in and out at 15 mm/s (the smoke test presses by script)
            const double before = press;
            press += 15.0 * dt * double((glfwGetKey(w, GLFW_KEY_W) == GLFW_PRESS) - (glfwGetKey(w, GLFW_KEY_S) == GLFW_PRESS));
            press += press_scroll;
            if (args.exercise) press = 12.0 * std::min(1.0, loop / 40.0);
            press = std::clamp(press, 0.0, 25.0);
            const Pose rest = scene.leg.probe_rest_pose(u, v);
            physics.command(pressed(rest, press, dt > 0 ? (press - before) / dt : 0.0));

            const physics::SurfaceSnapshot& snap = physics.latest();
            deformer.apply(snap.positions, scene.patch);
            scene.probe_pose = rest;
            scene.probe_pose.position += float(press) * rest.axis_y();
            elapsed += dt;
            if (elapsed - last_title > 0.2) {
                char title[160];
                std::snprintf(title, sizeof title, "echosim - probe %.1f mm in, %.1f N", press, snap.probe_force_N);
                glfwSetWindowTitle(w, title);
                last_title = elapsed;
            }

            scene_pass.set_view(scene.frame_view());
            if (presenter.draw(passes))
                ++presented;
            else
                glfwWaitEventsTimeout(0.05);  // minimised: do not spin
            if (args.exercise && loop > 10000) break;  // a window system that never shows the window
        }
        swapchains = presenter.swapchain_generation();
        physics.stop();
        const physics::RunnerStats st = physics.stats();
        std::printf("echosim run: physics stepped %lld times (%lld late), last probe force %.2f N\n", static_cast<long long>(st.steps),
                    static_cast<long long>(st.overruns), physics.latest().probe_force_N);
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

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <GLFW/glfw3.h>

#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/exercise_script.hpp"
#include "app/gpu_args.hpp"
#include "app/live_link.hpp"
#include "app/stop_signals.hpp"
#include "app/trainer_window.hpp"
#include "app/terminal_progress.hpp"
#include "app/volume_source.hpp"
#include "app/window_input.hpp"
#include "device/mouse_keyboard_device.hpp"
#include "device/null_device.hpp"
#include "device/scripted_device.hpp"
#include "device/openhaptics_device.hpp"
#include "device/simulated_arm.hpp"
#include "device/spacemouse_device.hpp"
#include "core/parse_number.hpp"
#include "gpu/window.hpp"
#include "haptics/probe_mapping.hpp"
#include "igtl/server.hpp"
#include "runner/guide_pass.hpp"
#include "runner/runner.hpp"

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

// The run's input, polled by the runner before the session advances: GLFW's events, then the
// window's mouse and keyboard (or the smoke test's script) to the window, the camera and the
// mouse-and-keyboard device (read only when it is the session's device).
class RunControls final : public runner::Input {
public:
    RunControls(std::unique_ptr<InputSource> source, std::shared_ptr<device::MouseKeyboardDevice> mouse, TrainerWindow* trainer,
                std::shared_ptr<runner::GuideSwitch> guides)
        : source_(std::move(source)), mouse_(std::move(mouse)), trainer_(trainer), guides_(std::move(guides))
    {
    }
    bool poll(runner::Runner& runner, double dt_s) override
    {
        glfwPollEvents();
        if (trainer_) trainer_->read_ui();  // before the probe's keys: a tapped key is read once (sticky keys)
        RunInput in = source_->poll(float(dt_s));
        if (trainer_) trainer_->filter(runner, in);  // the trainer's UI first: a name typed moves no probe
        if (in.quit) return false;
        apply_to_window(in, *runner.window());
        scene::OrbitCamera& camera = runner.scene().camera;
        if (in.reset_camera) camera.reset(camera.target);  // still on the probe it follows
        camera.orbit(in.orbit_yaw, in.orbit_pitch);
        camera.zoom(in.zoom);
        runner::apply(*runner.frame(), in.scanner);
        if (in.toggle_guides) guides_->shown = !guides_->shown;
        mouse_->feed(in.probe);
        return true;
    }

private:
    std::unique_ptr<InputSource> source_;
    std::shared_ptr<device::MouseKeyboardDevice> mouse_;
    TrainerWindow* trainer_;
    std::shared_ptr<runner::GuideSwitch> guides_;
};

// What the run says and shows beside the frame: the device's events (and, while it is away, the
// title says so), the title bar (the press and the force, five times a
// second of session time), the frames presented and the display rate; and when the run ends: the
// window closed, the frames asked for presented, or a signal (app/stop_signals.hpp).
class RunConsole final : public runner::Observer {
public:
    RunConsole(int frames, const StopSignals& stop) : frames_(frames), stop_(stop) {}

    void on_attach(runner::Runner& runner) override
    {
        window_ = runner.window();
        frame_ = runner.frame();
    }
    bool should_stop() override
    {
        return window_->should_close() || (frames_ != 0 && presented_ >= frames_) || stop_.requested() != 0;
    }
    void on_step(runner::StepContext& step) override
    {
        events_.clear();
        step.session.device()->events(events_);
        for (const device::DeviceEvent& e : events_) {
            std::printf("echosim run: %s: %s: %s\n", e.device.c_str(), device::to_string(e.kind), e.message.c_str());
            if (e.kind == device::DeviceEvent::Kind::connected) device_status_.clear();
            if (e.kind == device::DeviceEvent::Kind::disconnected || e.kind == device::DeviceEvent::Kind::access_denied)
                device_status_ = e.device + " " + device::to_string(e.kind);
            last_title_ = -1;
        }
        const session::SessionView& state = step.view;
        if (step.session.time() - last_title_ > 0.2) {
            char title[224];
            if (device_status_.empty())
                std::snprintf(title, sizeof title, "echosim - probe %.1f mm in, %.1f N - %s", state.press_mm, state.probe_force_N,
                              runner::scanner_status(*frame_).c_str());
            else
                std::snprintf(title, sizeof title, "echosim - %s: looking for it - probe %.1f N", device_status_.c_str(), state.probe_force_N);
            glfwSetWindowTitle(window_->handle(), title);
            last_title_ = step.session.time();
        }
    }
    void on_frame(const runner::FrameContext& frame) override
    {
        if (!frame.shown) return;
        last_shown_ = std::chrono::steady_clock::now();
        if (++presented_ == 1) first_shown_ = last_shown_;
    }

    int presented() const { return presented_; }
    // the display's time, from the first presented frame (set-up and the first frame's pipeline
    // compilation excluded) to the last
    double shown_s() const { return std::chrono::duration<double>(last_shown_ - first_shown_).count(); }

private:
    int frames_;  // stop after this many presented frames (0: until the window closes)
    const StopSignals& stop_;
    gpu::Window* window_ = nullptr;
    runner::SimulatorFrame* frame_ = nullptr;
    std::vector<device::DeviceEvent> events_;
    std::string device_status_;  // what the title says of the device while it is away
    double last_title_ = -1;
    int presented_ = 0;
    std::chrono::steady_clock::time_point first_shown_, last_shown_;
};

}  // namespace

int run_window(const RunArgs& args)
{
    // --igtl [PORT]: the link to 3D Slicer
    int igtl_port = 0;
    if (!args.igtl_port.empty() && (!parse_number(args.igtl_port, igtl_port) || igtl_port < 1 || igtl_port > 65535)) {
        std::fprintf(stderr, "echosim run: --igtl %s: a port number in 1..65535 (without one: %d)\n", args.igtl_port.c_str(), igtl::kDefaultPort);
        return kExitBadInput;
    }
    if (!args.igtl_bind.empty()) {
        if (args.igtl_port.empty()) {
            std::fprintf(stderr, "echosim run: --igtl-bind %s: give --igtl [PORT] too (the address is where the link listens)\n",
                         args.igtl_bind.c_str());
            return kExitBadInput;
        }
        if (const std::string why = igtl::bind_address_error(args.igtl_bind); !why.empty()) {
            std::fprintf(stderr, "echosim run: --igtl-bind %s\n", why.c_str());
            return kExitBadInput;
        }
    }
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

    // the link listens before the volume is made (a minute and a half the first time), so a port
    // already taken is said at once; the run then stops, rather than go on without the link asked for
    std::unique_ptr<igtl::Server> link;
    if (igtl_port != 0) {
        try {
            link = std::make_unique<igtl::Server>(igtl::ServerOptions{.port = igtl_port, .bind = args.igtl_bind});
        } catch (const igtl::ServerError& e) {
            std::fprintf(stderr, "echosim run: %s (is a PlusServer or another echosim serving it?); choose another with --igtl PORT\n", e.what());
            return kExitBadInput;
        }
        std::string where;
        for (const std::string& address : link->listening()) where += (where.empty() ? "" : " and ") + address;
        std::printf("echosim run: OpenIGTLink: serving %s, %s and %s on %s (%s); in 3D Slicer, connect OpenIGTLinkIF as a client "
                    "to %s, port %d\n",
                    igtl::kImageName, igtl::kProbeToReferenceName, igtl::kImageToReferenceName, where.c_str(),
                    args.igtl_bind.empty() ? "this machine alone; --igtl-bind ADDRESS serves others" : "no authentication: anyone who can reach it",
                    args.igtl_bind.empty() ? "localhost" : "this machine", link->port());
    }

    // the exam window follows a lifted probe over the whole leg (session/session.hpp)
    session::SessionOptions session_options{.clock = session::Clock::real_time, .window_follows_probe = true};
    if (!read_model_option("run", args.model, session_options.tissue)) return kExitBadInput;
    // the probe moves through the haptic loop: from the window's mouse and keyboard, a SpaceMouse,
    // a force-feedback arm (a Touch through OpenHaptics, or the simulated one), a scripted
    // trajectory, or nothing
    // the mouse and keyboard, and a SpaceMouse, slide the probe over the whole course (the patch
    // of the leg the window starts on is their frame: haptics/probe_mapping.hpp)
    const device::SurfaceLimits course = haptics::exam_limb_surface(scene::LegModel{});
    auto mouse = std::make_shared<device::MouseKeyboardDevice>(device::SurfacePlacement{}, course);
    try {
        if (!args.trajectory.empty())
            session_options.device = std::make_shared<device::ScriptedDevice>(device::Trajectory::load(args.trajectory), args.trajectory.string());
        else if (args.device == "spacemouse")
            session_options.device = std::make_shared<device::SpaceMouseDevice>(device::SpaceMouseMapping{.limits = course});
        else if (args.device == "openhaptics") {
            const device::hd::HdLoad hd = device::hd::load_hd_library();
            if (!hd.api)
                throw std::runtime_error("--device openhaptics: OpenHaptics' libHD.so not found (" + hd.error + "); " + device::hd::kInstallHint);
            session_options.device = std::make_shared<device::OpenHapticsDevice>(hd.api);
        } else if (args.device == "simulated-arm")
            session_options.device = std::make_shared<device::SimulatedArm>();
        else if (args.device == "null")
            session_options.device = std::make_shared<device::NullDevice>();
        else
            session_options.device = mouse;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim run: %s\n", e.what());
        return kExitBadInput;
    }
    VolumePair volumes;
    std::unique_ptr<TrainerWindow> trainer;
    const auto guides = std::make_shared<runner::GuideSwitch>();
    TerminalProgress progress(std::string("echosim run: ") + kCaseVolumeProgress);
    try {
        if (args.volume.empty() && !args.labels.empty())
            throw std::invalid_argument("--labels " + args.labels.string() + ": give the --volume they label");
        if (args.imaging == "generative" && !args.volume.empty() && args.labels.empty())
            throw std::invalid_argument("--imaging generative: synthesises the image from tissue labels; give --labels for " + args.volume.string());
        // the trainer (app/trainer_window.hpp): the chosen case's exam volume, or the user's own
        trainer = std::make_unique<TrainerWindow>(args);
        volumes = trainer->load_volumes(context_options(args.gpu), progress);
    } catch (const std::exception& e) {
        progress.finish();
        std::fprintf(stderr, "echosim run: %s\n", e.what());
        return kExitBadInput;
    }
    progress.finish();
    std::printf("echosim run: echographic volume: %s\n", volumes.description.c_str());

    // From here on a device may be driven: Ctrl-C or SIGTERM ends the run at its next frame, in
    // order (the device's force to zero, the summary), exit 128 + the signal
    // (app/stop_signals.hpp). Before, while the volume is made, either ends the process at once:
    // nothing is held then that needs letting go.
    const StopSignals stop;

    // The run is the runner's window configuration (runner/runner.hpp): the window, the session on
    // the real-time clock (the tissue in its own thread at 1 kHz; the window sends the probe and
    // draws the latest surface the physics published), the frame (the scene, and beside it the
    // echographic image made on the GPU every frame from the same physics step); what the run adds
    // is its input (RunControls), its console, title and limits (RunConsole) and the live link (LiveLink).
    auto console = std::make_shared<RunConsole>(args.frames, stop);
    const std::shared_ptr<LiveLink> live = link ? std::make_shared<LiveLink>(*link, "echosim run: ") : nullptr;
    std::uint32_t swapchains = 0, validation = 0;
    // one runner a case: a lesson started on another case ends it, and the run goes on with a
    // runner holding that case's volumes (app/trainer_window.hpp), in the same window (a kiosk's
    // stays fullscreen: the desk behind it never shows)
    std::shared_ptr<gpu::Window> window;
    for (bool again = true; again;) {
        runner::RunnerConfig config;
        config.name = "run";
        config.session = session_options;
        config.output = runner::Output::window;
        config.camera_follows_probe = true;
        config.window = {args.width, args.height, args.fullscreen, "echosim - compression ultrasound of the thigh"};
        config.gpu = context_options(args.gpu);
        config.volume = volumes.volume;
        config.labels = volumes.labels;
        config.observers.push_back(console);
        // with the link: every frame's image read back (a slot behind, no wait) and published with the
        // pose it was drawn at (app/live_link.hpp)
        if (live) config.observers.push_back(live);
        trainer->configure(config);
        // the practice guides (G): the case's vessels and the image plane in the leg, for the
        // phantom's own volumes (a volume of the user's has its own anatomy)
        if (args.volume.empty())
            config.passes.push_back(runner::guide_pass_factory(runner::course_guides(scene::LegModel{}, trainer->case_to_load().anatomy), guides));
        std::shared_ptr<const std::atomic<std::uint32_t>> messages;
        {
            config.shared_window = window;
            runner::Runner runner(std::move(config));
            window = runner.shared_window();
            messages = runner.validation_counter();
            trainer->attach(runner);
            session::Session& session = runner.session();
            if (!session.haptics_note().empty()) std::printf("echosim run: %s\n", session.haptics_note().c_str());
            std::printf("echosim run: %s, %ux%u; left-drag orbits, wheel zooms; right-drag or arrows slide the probe, "
                        "Q/E and A/D tilt it, R levels it, T turns it (transverse/longitudinal), W/S or Shift+wheel press it in and out; ] and [ depth, + and - gain, "
                        "Page Up and Page Down focus, Space freezes the image; V (or Home) resets the view; F11 fullscreen, Esc quits\n",
                        runner.context()->device_name().c_str(), runner.presenter()->extent().width, runner.presenter()->extent().height);

            std::unique_ptr<InputSource> input;
            if (args.exercise)
                input = std::make_unique<ExerciseScript>(glm::ivec2(args.width, args.height));
            else
                input = std::make_unique<WindowInput>(*runner.window());
            runner.set_input(std::make_shared<RunControls>(std::move(input), mouse, trainer.get(), guides));
            runner.run();  // ends stopping the session: the haptic loop first, which sends the device a zero force

            swapchains += runner.window_output()->swapchain_generation();
            std::printf("echosim run: the runner stepped %lld times\n", static_cast<long long>(runner.steps()));
            if (const int signal = stop.requested()) std::printf("echosim run: stopped by %s\n", StopSignals::name(signal));
            const physics::RunnerStats st = session.physics_stats();
            std::printf("echosim run: physics stepped %lld times (%lld late, %lld asleep), last probe force %.2f N\n",
                        static_cast<long long>(st.steps), static_cast<long long>(st.overruns), static_cast<long long>(st.asleep),
                        session.view().probe_force_N);
            if (haptics::HapticLoop* loop = session.haptic_loop()) {
                const haptics::PeriodStats h = loop->stats();
                std::printf("echosim run: haptic loop ticked %lld times; period error p50 %.3f ms, p99 %.3f ms, max %.3f ms; %lld missed deadlines\n",
                            static_cast<long long>(loop->ticks()), h.error_quantile_ms(0.5), h.error_quantile_ms(0.99), h.max_error_ms,
                            static_cast<long long>(h.missed_deadlines));
            }
        }
        validation += messages->load();  // read with the runner gone: its leaks count too
        trainer->detach();
        again = trainer->again() && stop.requested() == 0;
        if (again) {
            TerminalProgress making(std::string("echosim run: making the case's volume (once; it is cached): "));
            try {
                volumes = trainer->load_volumes(context_options(args.gpu), making);
            } catch (const std::exception& e) {
                making.finish();
                std::fprintf(stderr, "echosim run: %s\n", e.what());
                return kExitFailure;
            }
            making.finish();
            std::printf("echosim run: %s: %s\n", trainer->lesson_waits() ? "the lesson's case" : "the chosen case", volumes.description.c_str());
        }
    }
    const int presented = console->presented();
    const double shown_s = console->shown_s();
    std::printf("echosim run: presented %d frames, swapchain created %u times (%.1f frames/s)\n", presented, swapchains,
                presented > 1 && shown_s > 0 ? (presented - 1) / shown_s : 0.0);
    if (link) {
        link->stop();
        std::vector<igtl::ServerEvent> last;
        report_link(*link, last, "echosim run: ");
        const igtl::ServerStats st = link->stats();
        std::printf("echosim run: OpenIGTLink: sent %lld frames to %lld client%s (%lld frames published)\n",
                    static_cast<long long>(st.frames_sent), static_cast<long long>(st.clients_served), st.clients_served == 1 ? "" : "s",
                    static_cast<long long>(st.frames_published));
    }
    const std::uint32_t n = validation;
    if (n > 0) std::fprintf(stderr, "echosim run: Vulkan validation reported %u message(s)\n", n);
    if (const int signal = stop.requested()) return StopSignals::exit_code(signal);
    return n > 0 ? kExitValidation : kExitOk;
}

}  // namespace echosim::app

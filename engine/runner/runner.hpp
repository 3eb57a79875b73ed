// One runner (DESIGN.md §1, "runner"; STYLE.md 15): what a running simulator is, once. `run`
// (window, real time), `soak` (offscreen, real time), `haptics-demo` (no frame, lock-step) and the
// exam (offscreen, lock-step: runner/exam_config.hpp) are configurations of it (RunnerConfig), not
// loops of their own; what each does beyond the loop is an Input or an Observer.
//
// It owns, in the order they are made (and destroyed in reverse): the window (when the output is
// one), the Vulkan context, the scene (runner/default_scene.hpp: the session, its device and
// clock, the camera), the drawing thread's command pool, the presenter (runner/presenter.hpp:
// window or offscreen behind one verb) and the frame (runner/frame.hpp: the ordered passes, with
// the volumes uploaded). Output::none makes no GPU object at all (the haptics demo).
//
// One step (Runner::step):
//   1. every observer's should_stop(), and the configured step limit: any says stop, the run ends;
//   2. the step's dt: lock-step, RunnerConfig::lock_step_dt_s; real time, the wall clock since the
//      last step, within [min_dt_s, max_dt_s] (a stall, a dragged window, is no leap of the probe);
//   3. the input (Input::poll: the window's mouse and keyboard, a script) before the session moves;
//      it may end the run (the user quit);
//   4. session.advance(dt): in lock-step the physics and the haptic loop step here, on simulated
//      time; in real time they run on their threads, and a step that draws a frame first waits (at
//      most kAwaitDevice) for the haptic loop to read the device afresh, so the frame shows the
//      probe where the input just put it, not where it was a frame before (Session::await_device);
//   5. the session's view, once (the scene and the image show one physics step), to every
//      observer's on_step, where an observer may ask for this step's frame (and its pixels);
//   6. the frame, when it is drawn every step (Drawing::every_step) or one observer asked for it:
//      the passes set from the view, presented, and every observer's on_frame (the pixels with it
//      when asked for and the presenter can read back).
// When the run ends: the session stops (the haptic loop first, which sends the device a zero
// force), then every observer's on_finish.
//
// Observers see only the session's own types (session::SessionView, session::Session), nothing of
// the commands: the exam's scorer (engine/exam), the recorders (runner/recorders.hpp), the live
// link and the soak's sampler (engine/app) are all observers.
//
// Threads: one driver thread (the main thread with a window: GLFW's rule) makes the runner and
// calls every member; observers and the input are called on it.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/context.hpp"
#include "gpu/window.hpp"
#include "io/nrrd.hpp"
#include "io/png.hpp"
#include "runner/default_scene.hpp"
#include "runner/frame.hpp"
#include "runner/presenter.hpp"
#include "session/session.hpp"

namespace echosim::runner {

class Runner;

// The longest a real-time step waits for the haptic loop to read the device (step 4 below): two of
// its 1 ms ticks and some slack.
inline constexpr std::chrono::microseconds kAwaitDevice{3000};

// What a step hands its observers (step 5 above).
struct StepContext {
    std::int64_t step = 0;  // from 0
    double dt_s = 0;        // this step's
    double time_s = 0;      // the session's clock after this step's advance [s]
    const session::SessionView& view;  // this step's: probe pose, force, time, the echographic input
    session::Session& session;

    // Asks for this step's frame to be drawn (with Drawing::on_request; it is anyway with
    // every_step), and with `pixels` read back to the observers' on_frame (offscreen only).
    void want_frame(bool pixels = false)
    {
        frame_wanted = true;
        pixels_wanted = pixels_wanted || pixels;
    }
    bool frame_wanted = false, pixels_wanted = false;
};

// A frame drawn (step 6).
struct FrameContext {
    std::int64_t step = 0;
    const session::SessionView& view;
    bool shown = false;                    // false: nothing drawn (a minimised window)
    const io::RgbaImage* pixels = nullptr; // read back when asked for (offscreen), else null
};

struct FinishContext {
    std::int64_t steps = 0;       // steps taken
    std::int64_t frames = 0;      // frames shown
    double time_s = 0;            // the session's clock at the end [s]
};

class Observer {
public:
    virtual ~Observer() = default;
    // Once, when the observer joins a runner (made, or add_observer): the place to reach the
    // runner's parts (its frame, to turn a read-back on; its session) and to keep the runner.
    virtual void on_attach(Runner&) {}
    // Before every step; true ends the run there (a limit reached, a signal, the window closed).
    virtual bool should_stop() { return false; }
    virtual void on_step(StepContext&) {}
    virtual void on_frame(const FrameContext&) {}
    virtual void on_finish(const FinishContext&) {}
};

// Polled at step 3: the window's mouse and keyboard (the camera, the window, the probe), a script.
class Input {
public:
    virtual ~Input() = default;
    // false ends the run (the user quit); `dt_s` is the step's.
    virtual bool poll(Runner& runner, double dt_s) = 0;
};

enum class Output {
    none,       // no frame (no GPU at all)
    offscreen,  // an offscreen image (gpu/offscreen.hpp), readable
    window,     // a window (gpu/window.hpp)
};
enum class Drawing {
    every_step,  // a frame every step (the window, the soak)
    on_request,  // only the steps an observer asks for (StepContext::want_frame): an exam writing
                 // frames at a rate, or none
};

struct RunnerConfig {
    std::string name = "run";            // the configuration, for messages
    session::SessionOptions session;     // its clock is the runner's: real time or lock-step
    double lock_step_dt_s = 1.0 / 60.0;  // lock-step: each step's simulated time [s]
    double min_dt_s = 1e-4, max_dt_s = 0.1;  // real time: a step's dt kept within [s]
    std::int64_t max_steps = 0;          // the run ends after this many steps (0: no limit)

    Output output = Output::none;
    Drawing drawing = Drawing::every_step;
    gpu::ContextOptions gpu;             // with a window, its instance extensions are added
    VkExtent2D extent{1280, 720};        // offscreen
    gpu::WindowOptions window;           // a window's
    // a window made before, taken instead of making one from `window` (Output::window): one
    // window for a run's runners, so a kiosk's fullscreen window stays up while it changes case
    // (main thread, as every window); null: the runner makes its own
    std::shared_ptr<gpu::Window> shared_window;
    // the echographic volume and its labels (null: none, the paper's linear deformation); needed
    // for any output
    std::shared_ptr<const io::Volume> volume, labels;
    // `volume` stands in while the case's is being made: the image shows the IMAGES BEING MADE cue
    // (runner/image_cue.hpp), whatever the probe does
    bool volume_pending = false;
    // how the echographic image is made (echo::Imaging; generative needs the labels). Unset: as the
    // machine suits: generative on a GPU; interpolative on a CPU's Vulkan (lavapipe), where the
    // generative image halves the window's frame rate (bench/RESULTS.md), without labels, and for
    // labels larger than the device's texel buffers
    std::optional<echo::Imaging> imaging;
    std::vector<PassFactory> passes;     // the configuration's own passes (runner/frame.hpp)
    // the camera keeps the probe in frame (scene::OrbitCamera::follow, each step with the step's
    // dt): a trainee sliding from the groin to the knee is not left looking at an empty groin
    bool camera_follows_probe = false;

    std::vector<std::shared_ptr<Observer>> observers;
    std::shared_ptr<Input> input;
};

// How the echographic image is made where the configuration leaves it unset: generative where it
// keeps the pace (a GPU, not a CPU implementation) and can read the labels (as texels), else
// interpolative.
echo::Imaging default_imaging(const gpu::Context& ctx, const io::Volume* labels);

class Runner {
public:
    // Makes what the configuration asks for (above) and attaches its observers. Throws
    // std::invalid_argument naming the field of a configuration it cannot run (a step that is not
    // finite and positive, an output without a volume), and what set-up throws (no display, no
    // Vulkan device, a volume the device cannot hold).
    explicit Runner(RunnerConfig config);
    ~Runner();
    Runner(const Runner&) = delete;
    Runner& operator=(const Runner&) = delete;

    // One step (above); false once the run has ended (and every later call).
    bool step();
    // Steps until the run ends.
    void run()
    {
        while (step()) {
        }
    }
    // Ends the run now (the session stopped, the observers told); once, later calls do nothing.
    void finish();
    bool finished() const { return finished_; }

    void add_observer(std::shared_ptr<Observer> observer);
    void set_input(std::shared_ptr<Input> input) { config_.input = std::move(input); }

    const RunnerConfig& config() const { return config_; }
    std::int64_t steps() const { return steps_; }
    std::int64_t frames() const { return frames_; }
    DefaultScene& scene() { return *scene_; }
    session::Session& session() { return scene_->session; }

    // The GPU's parts, null with Output::none (and window() without a window).
    const gpu::Context* context() const { return ctx_.get(); }
    // counts the validation layer's messages; read it after the runner is gone, to count leaks
    std::shared_ptr<const std::atomic<std::uint32_t>> validation_counter() const { return messages_; }
    Presenter* presenter() { return presenter_.get(); }
    WindowOutput* window_output() { return window_output_; }
    gpu::Window* window() { return window_.get(); }
    // the window, to hand on to the next runner (RunnerConfig::shared_window)
    std::shared_ptr<gpu::Window> shared_window() const { return window_; }
    SimulatorFrame* frame() { return frame_.get(); }
    // how the frame's echographic image is made (RunnerConfig::imaging, resolved); with no frame,
    // the configuration's, or interpolative
    echo::Imaging imaging() const { return imaging_; }

    // The echographic image of `input` at full resolution, rendered now and read back with its
    // stages' outputs (image::EchoImageGpu::render; the deformed labels with `want_labels`), for the
    // image recorder and the exam's images. Offscreen only (it uses frame slot 0, which an offscreen
    // presenter has waited for): std::logic_error otherwise.
    echo::EchoImage echo_image(const echo::EchoFrame& input, bool want_labels = false);

private:
    double next_dt();

    RunnerConfig config_;
    std::shared_ptr<gpu::Window> window_;  // before the context: it outlives what presents to it
    std::unique_ptr<gpu::Context> ctx_;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages_;
    std::unique_ptr<DefaultScene> scene_;
    std::unique_ptr<gpu::CommandPool> commands_;
    std::unique_ptr<Presenter> presenter_;
    WindowOutput* window_output_ = nullptr;  // presenter_, when it is a window
    std::unique_ptr<SimulatorFrame> frame_;
    echo::Imaging imaging_ = echo::Imaging::interpolative;
    io::RgbaImage pixels_;  // read-backs land here (allocated once)
    std::int64_t steps_ = 0, frames_ = 0;
    bool finished_ = false;
    bool clock_started_ = false;
    std::chrono::steady_clock::time_point last_;
};

}  // namespace echosim::runner

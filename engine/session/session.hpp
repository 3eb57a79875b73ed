// One running simulator (DESIGN.md §1): the object the window, the headless commands, the
// benchmarks and the tests drive, so that each of them is a few lines over it (STYLE.md 13).
//
// It owns:
//   - the leg (the skin the tissue model is built on, and the render patch it deforms);
//   - the tissue model at the resolution the physics runs at in real time, compiled once for the
//     physics, and its physics runner;
//   - the probe: where the driver rests it on the skin and how far it presses it in;
//   - the one path by which probe commands reach the physics (below);
//   - the patch deformer that carries the tissue's surface onto the render patch;
//   - the clock: real time (wall-clock seconds since the session began; the physics thread steps on
//     its own, every PhysicsOptions::time_step of them), or lock-step on simulated time (advance()
//     runs the steps in the caller's thread: headless runs, exams and tests are reproducible step
//     for step).
//   - the echographic image's input: the image plane, the patient's case, and each frame's probe
//     and indentation (echo::EchoFrame), made from the very physics snapshot whose force the view
//     reports, so the image and the force always show the same moment. The image pipeline itself
//     (engine/image, on the GPU, or the CPU twin) draws it, as the scene pass draws the patch; the
//     volumes it reads are the caller's.
//   - optionally a device (SessionOptions::device) and the haptic loop that reads it: then the
//     device, not place_probe, moves the probe (below).
//
// Threads and hand-offs. One driver thread (the window's main thread, a headless command, a test)
// calls every member. The probe command path: the driver sets the probe (place_probe), and
// advance() turns it into one physics::ProbeCommand, with the press speed from the change since the
// last advance, and hands it to PhysicsRunner::command: a lock-free triple buffer, latest wins.
// Its consumer is the physics thread (real time) or advance() itself (lock-step). The surface comes
// back the same way: the physics publishes a snapshot after every step, and view() reads the newest
// (the driver thread is its one reader). Nothing else crosses threads.
//
// The exam window. The tissue is simulated on a patch of the leg the size of the home patch (about
// 120 mm along the limb by 75 mm around it, 2500 nodes at refine 7: the largest grid that steps at
// 1 kHz on one core), and the patch is a window that follows the probe over the whole right leg,
// from the inguinal ligament to the popliteal fossa. The rule (follow_probe(), at every advance):
//   - the window moves only while the probe is lifted: the tissue pushes on it less than
//     kLiftedForceN (off the skin, or resting on it in the gel without pressing) and its face is
//     not more than kMaxInsideMm inside the skin (a probe pushed into the leg off the simulated
//     tissue feels nothing there, but is not lifted: the window does not appear around it), and
//     its face is within kHoverMm of the skin (a probe waved about the room moves nothing);
//   - it moves when the face centre has left the window's central zone: more than kZoneAlongMm
//     along the limb or kZoneAroundMm around it from the window's centre (measured on the skin);
//   - it then re-centres on the face: a new leg (its static mesh's hole where the window is now),
//     the tissue model on it, compiled, a new patch deformer; the physics runner swaps the model
//     in (PhysicsRunner::replace_model: the tissue at rest, the clock and the probe carried on).
// A probe pressed never has the window moved under it: it presses where it was put down. Pressed
// near the window's edge it still presses modelled tissue, since the window is three times as long
// as the face is wide across the beam and the zone keeps the face well inside (along: the face's
// 10 mm in 105 mm of tissue grid; around: the face's 40 mm in 66 mm); pressed and slid beyond the
// tissue grid, the face loses the nodes under it (SessionView::over_model says so) until it is lifted
// and put down again. The window's placement is in window(), its moves counted by window_serial():
// whoever draws the leg uploads the static mesh and the patch again when that changes
// (render::ScenePass::replace_leg), and leg() then is the new one.
// Real time: the new window is built on a thread of its own, at a lower priority (nice 10), while
// the physics steps on and the driver draws frames; a later advance() that finds it built, the
// probe still lifted and still wanting that window, swaps it in: the physics thread is stopped,
// the model swapped and the thread started again (a millisecond or two; the lift is checked again
// once it is stopped, and a probe pressed meanwhile keeps the old window). The builder reads only
// what the session never changes after it is made (the parameters, the options); the window comes
// back through its std::future. The haptic loop keeps ticking throughout: it renders the contact model the
// swap publishes ("no contact": the probe was lifted) until the new model's first step. Lock-step:
// all of it in advance(), on simulated time: runs with moves are repeatable bit for bit.
//
// With a device, the haptic loop (haptics/haptic_loop.hpp) is the probe's one commander instead: in
// real time on its own 1 kHz thread, in lock-step ticked by advance() at its rate, between the
// physics steps. The driver then feeds the device (the window's mouse and keyboard) or leaves it to
// its own thread (HID), and reads the loop's latest tick in view(): the probe where the device put
// it and the force the hand feels, beside the physics snapshot. place_probe and the press helpers
// are for sessions without a device.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.hpp"
#include "device/device.hpp"
#include "haptics/haptic_loop.hpp"
#include "haptics/probe_mapping.hpp"
#include "physics/compiled_model.hpp"
#include "physics/physics_options.hpp"
#include "physics/physics_runner.hpp"
#include "scene/leg.hpp"
#include "echo/echo_frame.hpp"
#include "session/indentation.hpp"
#include "session/patch_deformer.hpp"
#include "session/simulation_model.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::session {

enum class Clock {
    real_time,  // the physics thread steps on wall-clock time
    lock_step,  // advance() steps the physics on simulated time, in the caller's thread
};

struct SessionOptions {
    Clock clock = Clock::lock_step;
    int refine = kSimulationRefine;  // tissue grid refinement (7: 2500 nodes)
    physics::PhysicsOptions physics;
    echo::ImagePlane image;   // the echographic image's plane and pixels
    echo::PatientCase patient;
    // the tissue's parameters (a fitted model's samples, tissue/tissue_json.hpp); none: the shipped
    // thigh's (assets/models/thigh.json)
    std::optional<tissue::SampleParameters> tissue;
    // the device that moves the probe through the haptic loop; none: the driver places it
    std::shared_ptr<device::Device> device;
    haptics::HapticOptions haptics;
    // The exam window (above): whether it follows the probe, and where it starts (none: the home
    // patch over the common femoral vein). Off unless asked: the paper's Fig. 8 slide (haptics-demo,
    // the soak, the haptics bench) starts lifted 19 mm around from the home patch's centre and
    // slides 38 mm across it pressing, which a window re-centred at its start would not cover; an
    // exam, `run` and `render` at a pose off the home patch turn it on.
    bool window_follows_probe = false;
    std::optional<scene::LimbCoordinates> window_centre;
    // A patient whose subcutaneous tissue is deeper than the thigh the model was fitted on (a large
    // patient, issue 31's case files: the fat thickness), as a factor on the depth of the tissue
    // column under each node: 1 is the fitted thigh (exactly: nothing is scaled), 2 a column twice
    // as deep. The column is the non-linear spring F(c) = c / (b - a c) (tissue/nonlinear_spring.hpp):
    // a column k times as deep, of the same tissue, compresses k times as far under the same
    // force (springs in series), c_k(F) = k c(F) = k b F / (1 + a F), so b becomes k b and a stays:
    // the rest stiffness 1/b falls by k and the depth where it bottoms out, b/a, grows by k. The
    // probe then travels k times as far, at the same force, before the tissue stiffens; the echo
    // side (the vein deeper under more fat, and collapsing under the pressure the force makes over
    // the face) is the case's phantom's. Within [0.25, 4].
    double tissue_depth_scale = 1.0;
};

// The probe the driver holds: resting on the skin at `rest` (the face on the skin, the beam along
// the inward normal) and pressed `press_mm` along its beam.
struct ProbePlacement {
    Pose rest;
    double press_mm = 0;  // [mm], >= 0
    Pose face() const { return pressed_along_beam(rest, press_mm); }
};

// How a press settled (Session::press_and_settle). The force is the mean over the last
// kSettleWindowS, what a force gauge would read, with how much it moves within the window: a model
// that rings or a contact that chatters shows there (the shipped thigh's presses, 25 mm deep
// included, move less than a millinewton: bench/RESULTS.md, "Settling").
struct SettleReport {
    bool settled = false;
    double press_mm = 0;  // the press it settled under [mm]
    double seconds = 0;   // simulated time from the start of the press [s]
    double force_N = 0;   // the tissue's mean push on the probe over the last window
    double drift_N = 0;   // how much that mean moved since the window before [N]
    double ripple_N = 0;  // half the force's peak-to-peak within the last window [N]
    int resets = 0;       // times the physics reset an exploded state during the press
};
inline constexpr double kSettleWindowS = 0.05;  // [s]
inline constexpr double kMaxSettleS = 3.0;       // [s] of simulated time
// settled: the window's mean moved by less than this (2 mN, or 0.5 % of a larger force), and the
// physics did not reset
inline double settled_change_N(double force_N) { return std::max(0.002, 0.005 * std::abs(force_N)); }
// "the tissue has not settled under a P mm press after S s ...": what to say instead of a force
std::string not_settled_message(double press_mm, const SettleReport& report);

// What the simulation looks like now, for the scene pass (through the frame view) and the user.
struct SessionView {
    const std::vector<scene::Vertex>* patch = nullptr;  // the render patch, deformed by the tissue
    Pose probe;               // where the probe's face is (its commanded pose)
    double press_mm = 0;      // [mm]
    double probe_force_N = 0; // the tissue's push on the probe along its axis (latest step)
    double time_s = 0;        // simulated time of the latest step
    int resets = 0;           // times the physics recovered from an unstable state
    // with a device: the force the haptic loop rendered at its latest tick (what the hand feels,
    // within the device's limits) and whether the device is there
    double haptic_force_N = 0;
    bool device_connected = true;
    // the probe against the simulated tissue at the same step: whether it touches the skin (the
    // step found contacts), whether its face lies over the tissue the window simulates (its
    // footprint within the window's tissue grid: off it, a press meets nothing), and the window it
    // is simulated on (its centre, and its serial: a change means the leg must be drawn again)
    bool in_contact = false;
    bool over_model = true;
    scene::LimbCoordinates window_centre;
    int window_serial = 0;
    // the echographic image's input at the same step: the pressed face, the skin under it per
    // image column (none while the probe does not touch the skin), the pressure of probe_force_N
    // over the face, the time
    const echo::EchoFrame* echo = nullptr;
};

class Session {
public:
    explicit Session(const SessionOptions& options = {});
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    // The leg with the exam window where it is now: a new object each time the window moves
    // (window_serial() counts the moves), so a reference to it holds until the next advance().
    const scene::LegModel& leg() const { return *leg_; }
    static constexpr double kMaxPressMm = 25.0;  // the deepest the driver may press [mm]

    // The exam window (above): the patch the tissue is simulated on (its cells and extent on the
    // exam limb), and how many times it has moved.
    const scene::ExamPatch& window() const { return leg_->patch(); }
    int window_serial() const { return window_serial_; }
    static constexpr double kLiftedForceN = 0.5;  // [N] the probe counts as lifted below this push
    static constexpr double kHoverMm = 40.0;      // [mm] the face within this of the skin, outside
    static constexpr double kMaxInsideMm = 1.0;   // [mm] and no deeper than this inside it
    static constexpr double kZoneAlongMm = 20.0;  // [mm] the central zone's half-length along the limb
    static constexpr double kZoneAroundMm = 8.0;  // [mm] and its half-width around it
    // Where a face centre lies from the window's centre, along the limb (towards the foot) and
    // around it (towards the window's increasing theta) [mm], on the skin; and its height above it.
    struct WindowOffset {
        double along_mm = 0, around_mm = 0, height_mm = 0;
    };
    WindowOffset window_offset(const Pose& face) const;
    // Whether the whole face (40 by 10 mm) of a probe at `face` lies over the window's tissue grid.
    bool over_model(const Pose& face) const;
    // Moves the window now to be centred as near `centre` as whole leg cells allow, pressing or not
    // (a scripted exam's start, tests, a driver that knows better); false when it is there already.
    // The same swap as a move that follows the probe, without the lift check, built in this thread.
    bool move_window(scene::LimbCoordinates centre);
    // How the moves went: how many, and how long the last and the longest took in the driver
    // thread: building the new window (the physics steps on meanwhile in real time), and the swap
    // itself (real time: the physics thread stopped; the haptic loop renders "no contact").
    struct WindowMoves {
        int moves = 0;
        int abandoned = 0;  // real time: built, but the probe was pressed by the time of the swap
        double last_build_ms = 0, max_build_ms = 0;
        double last_swap_ms = 0, max_swap_ms = 0;
    };
    const WindowMoves& window_moves() const { return window_moves_; }

    const tissue::TissueModel& tissue_model() const { return compiled_->tissue; }
    const physics::CompiledModel& compiled_model() const { return *compiled_; }
    Clock clock() const { return options_.clock; }
    double time() const { return time_; }  // [s] of the session clock, as of the last advance()

    // The probe the driver holds; it reaches the physics at the next advance(). Throws
    // std::invalid_argument naming what is wrong with a placement the physics could not take (a
    // position that is not finite, a quaternion that is not a rotation, a negative press); the
    // probe stays where it was.
    const ProbePlacement& probe() const { return probe_; }
    void place_probe(const ProbePlacement& placement);
    // The probe on the exam patch at (u, v) in [0,1]^2, pressed `press_mm`.
    void place_probe_on_patch(float u, float v, double press_mm);

    // The device moving the probe (null without one), its haptic loop, and the loop's note on its
    // priority ("" when it runs real-time, or with no loop thread).
    device::Device* device() const { return options_.device.get(); }
    haptics::HapticLoop* haptic_loop() const { return haptics_.get(); }
    const std::string& haptics_note() const { return haptics_note_; }

    // Sends the probe to the physics, its press speed taken over `dt` [s] (the frame's duration, > 0),
    // and moves the clock on: in lock-step by `dt`, stepping the physics to the new time here; in
    // real time to the wall clock. With a device, lock-step ticks the haptic loop every period up to
    // the new time, stepping the physics in between; real time leaves both to their threads.
    void advance(double dt);
    // Real time with a device: waits, at most `at_most`, for the haptic loop to read the device
    // afresh (two ticks from now: the one under way may have read it before), so a view taken next
    // shows what an input given just before did (a probe moved: the image plane moved). Returns
    // at once in lock-step, without a device, or with the loop stopped. The driver's thread.
    void await_device(std::chrono::microseconds at_most);
    // Lock-step: presses the probe resting at `rest` in to `press_mm` over 0.1 s, then holds it
    // for at least `settle_s` of simulated time and on until the tissue has settled under it (the
    // mean force on the probe over kSettleWindowS moves by less than settled_change_N from one
    // window to the next), giving up after kMaxSettleS. Whoever reports the force must look at `settled` first: a model that creeps
    // would otherwise report a force it has not reached.
    SettleReport press_and_settle(const Pose& rest, double press_mm, double settle_s = 0.4);
    // Lock-step: presses the probe resting at `rest` until the tissue pushes back with `force_N`
    // (within 2 %, settled as press_and_settle settles), and returns how it settled there. Throws
    // std::invalid_argument when the force is not finite and positive, or out of reach of the
    // deepest press (25 mm), naming the force it reaches there, and std::runtime_error when the
    // tissue does not settle.
    SettleReport press_to_force(const Pose& rest, double force_N);

    // The newest physics state on the render patch (deformed again only when a new step arrived).
    const SessionView& view();
    const echo::ImagePlane& image_plane() const { return options_.image; }
    const echo::PatientCase& patient() const { return options_.patient; }
    physics::RunnerStats physics_stats() const { return physics_.stats(); }
    // Stops the physics thread (real time); the view keeps the last state. Also on destruction.
    void stop();

private:
    struct Window {
        double build_ms = 0;
        std::unique_ptr<const scene::LegModel> leg;
        std::shared_ptr<const physics::CompiledModel> compiled;
        physics::TissueState rest;  // the tissue at rest on it, made before the swap
        std::unique_ptr<PatchDeformer> deformer;
    };
    Window build_window(std::unique_ptr<const scene::LegModel> leg) const;
    // the tissue model on `leg`'s window: the fitted parameters, each node's column scaled to the
    // skin it carries there against what it carries on the home patch
    tissue::TissueModel window_tissue(const scene::LegModel& leg) const;
    // the probe's face as the physics is commanded it now (the device's, with one)
    Pose commanded_face();
    // the rule above; at the start of every advance()
    void follow_probe();
    // the probe lifted as the rule has it (the push, the face's height), its face's offset in `offset`
    bool lifted(WindowOffset& offset);
    // builds the window at `centre` and swaps it in; `if_lifted`: only if the probe is still
    // lifted once the physics is stopped, and in real time built on the builder thread (the swap
    // then comes at a later call that finds it built). False when it did not move.
    bool move_to(scene::LimbCoordinates centre, bool if_lifted);
    bool swap_in(Window next, bool if_lifted);

    SessionOptions options_;
    tissue::TissueModel fitted_;  // the tissue's parameters (scaled by tissue_depth_scale), fit and provenance
    std::vector<double> home_mass_;  // each node's mass on the home patch (its share of the skin)
    std::unique_ptr<const scene::LegModel> home_leg_;  // where the window starts; the device mapping's, for good
    std::unique_ptr<const scene::LegModel> moved_leg_;  // the window's leg once it has moved
    const scene::LegModel* leg_ = nullptr;               // the one of the two the window is on
    std::shared_ptr<const physics::CompiledModel> compiled_;
    physics::PhysicsRunner physics_;
    haptics::ProbeMapping mapping_;
    std::unique_ptr<haptics::HapticLoop> haptics_;  // with a device
    std::string haptics_note_;
    double haptic_time_ = 0;  // lock-step: the last tick's time [s]
    std::unique_ptr<PatchDeformer> deformer_;
    IndentationProfile indentation_;
    int window_serial_ = 0;
    WindowMoves window_moves_;
    bool stopped_ = false;  // stop() was called: nothing starts the physics thread again
    // real time: the window being built on the builder thread, and its cells
    std::future<Window> pending_;
    scene::PatchCells pending_cells_;
    ProbePlacement probe_;
    double sent_press_mm_ = 0;  // the press of the last command sent [mm]
    double time_ = 0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();  // real time's origin
    std::int64_t shown_step_ = 0;  // the physics step the view shows (0: the rest state, as the leg gives it)
    std::vector<scene::Vertex> patch_;
    SessionView view_;
    echo::EchoFrame echo_;
};

}  // namespace echosim::session

// The physics thread (DESIGN.md §2, "Threads"): steps the tissue at a fixed rate and publishes a
// snapshot of the surface after every step. Hand-offs, all lock-free triple buffers:
//   in:  ProbeCommand      (latest wins) from one producer thread, the one that moves the probe (the
//                          simulator session's driver: session/session.hpp)
//   out: SurfaceSnapshot   (latest wins) to one reader, the session's driver, which draws it
//   out: LocalContactModel (latest wins) to one reader, the haptic thread
// Headless runs do not start the thread: step_to(t) runs the same steps in the caller's thread on
// simulated time, so an exam or a test is reproducible step for step (on one machine, with one
// PhysicsOptions::threads: see core/simd.hpp and core/fork_join.hpp on what can change the last bits).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/fork_join.hpp"
#include "physics/compiled_model.hpp"
#include "physics/local_contact_model.hpp"
#include "physics/physics_options.hpp"
#include "physics/step.hpp"
#include "physics/tissue_state.hpp"
#include "core/triple_buffer.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

// Where the probe is to be: the contact's probe state, handed to the physics as a whole (make one
// from a pose with contact::probe_at).
using ProbeCommand = contact::ProbeState;

// Why a command cannot drive the probe ("position is not finite", "orientation is not a rotation",
// ...), or empty when it can.
std::string probe_command_error(const ProbeCommand& c);

struct SurfaceSnapshot {
    double time = 0;                 // simulated [s]
    std::int64_t step = 0;
    std::vector<float> positions;    // 3 per node [mm]
    double probe_force_N = 0;        // the tissue's push on the probe along its axis
    int contacts = 0;
    int cg_iterations = 0;
    int resets = 0;
};

struct RunnerStats {
    std::int64_t steps = 0;     // steps, a stride (below) counted as the time steps it covers (a publish of steps_per_publish counts one)
    std::int64_t overruns = 0;  // steps that started later than one period after they were due
    std::int64_t asleep = 0;    // steps the tissue slept through (PhysicsOptions::sleep_speed)
    std::int64_t refused_commands = 0;  // probe commands with a NaN, infinity or bad rotation
    std::int64_t strides = 0;   // steps that covered several time steps at once (PhysicsOptions::clear_stride)
};

class PhysicsRunner {
public:
    // compiles the model (compile_model: a copy, so the caller's need not outlive the runner)
    PhysicsRunner(const tissue::TissueModel& model, const PhysicsOptions& options);
    // steps a compiled model that others (tests, benches, a second runner) may share
    explicit PhysicsRunner(std::shared_ptr<const CompiledModel> model);
    ~PhysicsRunner();
    PhysicsRunner(const PhysicsRunner&) = delete;
    PhysicsRunner& operator=(const PhysicsRunner&) = delete;

    // one producer thread. A command with an error (probe_command_error) is refused, counted and false:
    // the probe keeps its last good command, so a glitching device cannot blow up the tissue;
    // the caller, who knows the device, reports it.
    bool command(const ProbeCommand& c);
    // one reader thread (the session's driver)
    const SurfaceSnapshot& latest() { return out_.read(); }
    // the haptic thread (one reader): the skin under the probe, to render between steps
    const LocalContactModel& latest_contact() { return contact_out_.read(); }

    // headless: step in this thread until the simulated time reaches t (not while running). While
    // the probe is clear of the skin a step may cover several time steps
    // (PhysicsOptions::clear_stride), ending at t at the latest, or at `horizon` when that is later:
    // a caller that steps on to a known time in small pieces (the session's lock-step haptic
    // ticks, 1 ms each, within a frame's advance) lets the physics run ahead of the piece, to the
    // frame's end, while nothing touches the skin; the next step_to calls then find it there.
    void step_to(double t);
    void step_to(double t, double horizon);

    // real time: a thread stepping every options.time_step of wall-clock time
    void start();
    void stop();
    RunnerStats stats() const { return {steps_.load(), overruns_.load(), asleep_.load(), refused_.load(), strides_.load()}; }
    // Runs in the stepping thread after each step is published, with the step's number: for
    // instrumentation, and for the test that stalls the physics to show the haptic loop does not
    // wait for it. Set it while no thread steps.
    void set_after_step(std::function<void(std::int64_t step)> hook) { after_step_ = std::move(hook); }

    // Swaps in another compiled model of as many nodes (the exam window moved: session/session.hpp)
    // while no thread steps (after stop(), before start(); lock-step: between step_to calls), from
    // the driver thread. The tissue starts at rest on the new model; the clock, the step count, the
    // counters and the probe (so it does not enter again from behind its face) carry on. Publishes
    // the rest state as the latest snapshot and a contact model that says "no contact" at once, so
    // the driver and the haptic thread (which keeps ticking, reading it) never see the old model's
    // surface or contact after the swap. Throws std::invalid_argument, changing nothing, for a
    // model of another node count or thread count, and std::logic_error while the thread runs.
    void replace_model(std::shared_ptr<const CompiledModel> model);
    // The same with the new model's rest state made beforehand (make_state(*model), the swap's
    // longest part: the caller makes it while the physics still steps). Throws
    // std::invalid_argument for a state not of the model's size.
    void replace_model(std::shared_ptr<const CompiledModel> model, TissueState rest);

    // the immutable model it steps (any thread but while replace_model runs), and the tissue model that was compiled
    const std::shared_ptr<const CompiledModel>& compiled() const { return model_; }
    const tissue::TissueModel& model() const { return model_->tissue; }

private:
    void step_once(int stride = 1);
    // the time steps the next step may cover, before `until` (lock-step: step_to)
    int stride_before(double until);

    std::shared_ptr<const CompiledModel> model_;
    TissueState state_;  // owned by whichever thread steps: the physics thread while it runs
    ForkJoin team_;      // execution: the threads that share a step (model_->options.threads), driven by that same thread
    TripleBuffer<ProbeCommand> in_;
    TripleBuffer<SurfaceSnapshot> out_;
    TripleBuffer<LocalContactModel> contact_out_;
    std::function<void(std::int64_t)> after_step_;
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::atomic<std::int64_t> steps_{0}, overruns_{0}, asleep_{0}, refused_{0}, strides_{0};
};

}  // namespace echosim::physics

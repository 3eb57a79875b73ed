// The exam's configuration of the runner (issue 31): headless, offscreen, lock-step on simulated
// time, bit-for-bit repeatable: the same options (case, tissue, volume, trajectory, step, rate)
// give the same steps, the same observations and the same frame bytes, run after run.
//
//   - the clock: Clock::lock_step, a fixed `dt_s` a step (1/60 s by default); the physics and the
//     haptic loop step inside Session::advance, on simulated time, in the caller's thread;
//   - the probe: a scripted device playing a trajectory (device/trajectory.hpp, once, holding its
//     last pose), or the caller's session.device, or none: then the caller moves the probe, e.g.
//     from an Input (runner.hpp), which is polled before each advance;
//   - the length: `duration_s` of simulated time, or the trajectory's (rounded up to whole steps);
//   - frames: the offscreen frame (leg + image panel + cue) drawn only at the steps an observer
//     asks for; with `frames_per_s` > 0 a FrameRecorder (runner/recorders.hpp) writes them to
//     `frames_dir` at that rate of simulated time; with `draws` false no frame is made at all
//     (Output::none: no GPU object, no volume uploaded), for an exam whose observers never ask for
//     one (`echosim exam --frames-per-s 0`: its station images are the CPU twin's);
//   - observers: the caller's (the exam's scorer through a thin adapter, an ImageRecorder at the
//     stations' deepest presses, a force log) in `observers`, or added to the runner later.
//
// How the lead runs an exam (`echosim exam`):
//
//     runner::ExamOptions o;
//     o.session.patient = ...;                       // the case
//     o.volume = volumes.volume; o.labels = volumes.labels;
//     o.trajectory = device::Trajectory::load(path); o.trajectory_name = path.string();
//     o.frames_per_s = 10; o.frames_dir = out / "frames";
//     auto scorer = std::make_shared<ScorerObserver>(...);   // a runner::Observer
//     o.observers.push_back(scorer);
//     runner::Runner runner(runner::exam_config(std::move(o)));
//     while (runner.step()) {}                        // or runner.run()
//     // the run has finished: scorer->...() holds the result; runner.validation_counter()
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/trajectory.hpp"
#include "runner/runner.hpp"

namespace echosim::runner {

struct ExamOptions {
    session::SessionOptions session;  // the case (patient), the tissue, a device; the clock is set here
    std::shared_ptr<const io::Volume> volume, labels;
    std::optional<echo::Imaging> imaging;  // the scenario's (RunnerConfig::imaging: unset, as the machine suits)
    std::optional<device::Trajectory> trajectory;  // a scripted device playing it (instead of session.device)
    std::string trajectory_name = "the exam's trajectory";
    double dt_s = 1.0 / 60.0;        // simulated seconds a step
    double duration_s = 0;           // 0: the trajectory's end (required without a trajectory)
    double frames_per_s = 0;         // 0: no frames written
    bool draws = true;               // false: no frame at all (above); frames_per_s must then be 0
    std::filesystem::path frames_dir;
    gpu::ContextOptions gpu;
    VkExtent2D extent{1280, 720};
    std::vector<std::shared_ptr<Observer>> observers;
    std::shared_ptr<Input> input;
};

// The configuration (above). Throws std::invalid_argument naming the option at fault (a step or a
// length that is not finite and positive, frames without a folder, frames without drawing).
RunnerConfig exam_config(ExamOptions options);

// How many steps of `dt_s` cover `duration_s` (rounded up, a hair's tolerance for decimal steps).
std::int64_t steps_covering(double duration_s, double dt_s);

}  // namespace echosim::runner

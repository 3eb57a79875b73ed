// One scripted exam, end to end (issue 31 item 5), shared by `echosim exam`, `echosim bench exam`
// and the tests: the runner's exam configuration (runner/exam_config.hpp) plays the script in
// lock-step on simulated time while the scorer (exam/scorer.hpp) watches each step; afterwards
// each station's deepest press is imaged on the CPU twin of the image pipeline (the same bytes on
// every machine: the report's images and the deformed labels its compression is measured in), and
// the report is written: frames (at a rate, or none), the station images, force.csv, report.json,
// report.html and summary.png.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "app/volume_source.hpp"
#include "device/trajectory.hpp"
#include "exam/exam_report.hpp"
#include "exam/exam_script.hpp"
#include "exam/scenario.hpp"
#include "exam/station_truth.hpp"
#include "gpu/context.hpp"

namespace echosim::app {

class StopSignals;

// What an exam needs, read and checked (prepare_exam).
struct PreparedExam {
    exam::Scenario scenario;
    std::vector<exam::StationTruth> truth;
    device::Trajectory trajectory;
    std::string trajectory_name;
    std::vector<exam::TimedCall> calls;
};

// The case (a file; else a shipped id, "random" drawn with `seed`; else healthy), its stations'
// truth, and the script (a file; else the case's shipped correct exam). Throws naming the file and
// the field at fault.
PreparedExam prepare_exam(const std::filesystem::path& scenario_file, const std::string& case_id, std::uint64_t seed,
                          const std::filesystem::path& script);

struct ExamRunOptions {
    double frames_per_s = 10;  // 0: no frames, images at the stations only
    std::filesystem::path out; // the report's folder (made)
    gpu::ContextOptions gpu;
    std::string trainee;
    const StopSignals* stop = nullptr;  // checked every step: a signal ends the run without a report
    std::optional<echo::Imaging> imaging;  // how the image is made; unset: as the scenario says
};

struct ExamRunResult {
    exam::ExamReport report;   // valid when !stopped
    bool stopped = false;
    std::int64_t steps = 0, frames = 0;
    double simulated_s = 0;    // the exam's length on the session's clock
    double run_wall_s = 0;     // the runner's steps, frames written included [s]
    double report_wall_s = 0;  // imaging the stations and writing the report [s]
    std::uint32_t validation_messages = 0;
    echo::Imaging imaging = echo::Imaging::interpolative;  // how the exam's images were made (the runner's)
};

// Runs the exam and writes its files into options.out. Throws std::runtime_error naming what failed
// (a file that cannot be written, the GPU).
ExamRunResult perform_exam(const PreparedExam& exam, const VolumePair& volumes, const ExamRunOptions& options);

}  // namespace echosim::app

// Suite "exam": the shipped extended exam of the healthy case (CFV, SFJ, the femoral vein every
// 2 cm to the canal, the popliteal vein) played headless in lock-step on lavapipe, as `echosim exam`
// plays it (app/exam_run.hpp), against the simulated time it covers (DESIGN.md §5, "exam"):
//   - frames-10: frames written at 10 per simulated second; goal: at least real time;
//   - stations-only: no frames, the image at each station's deepest press; goal: at least 5x.
// realtime_x is the simulated seconds over the runner's wall seconds (the physics, the haptic loop
// ticked between its steps, the scorer, the frames); total_x counts the stations' imaging and the
// report's writing too. The case's volume is made first, once (cached), outside the timing.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

#include "app/exam_run.hpp"
#include "app/exam_volume.hpp"
#include "bench/suites.hpp"

namespace echosim::bench {
namespace {

void exam_row(benchmark::State& state, const gpu::ContextOptions& gpu, double frames_per_s)
{
    const app::PreparedExam exam = app::prepare_exam({}, "healthy", 1, {});
    const app::VolumePair volumes = app::exam_volume(exam.scenario, false, gpu, {});
    const std::filesystem::path out = std::filesystem::temp_directory_path() / ("echosim-bench-exam-" + std::to_string(::getpid()));
    for (auto _ : state) {
        std::filesystem::remove_all(out);
        const app::ExamRunResult r = app::perform_exam(exam, volumes, {.frames_per_s = frames_per_s, .out = out, .gpu = gpu, .trainee = "bench"});
        state.counters["simulated_s"] = r.simulated_s;
        state.counters["run_wall_s"] = r.run_wall_s;
        state.counters["report_wall_s"] = r.report_wall_s;
        state.counters["realtime_x"] = r.run_wall_s > 0 ? r.simulated_s / r.run_wall_s : 0;
        state.counters["total_x"] = r.simulated_s / (r.run_wall_s + r.report_wall_s);
        state.counters["frames"] = double(r.frames);
        state.counters["steps"] = double(r.steps);
        state.counters["stations"] = double(r.report.stations.size());
        state.counters["score"] = r.report.score;
    }
    std::filesystem::remove_all(out);
}

}  // namespace

std::shared_ptr<void> register_exam(const SuiteOptions& options)
{
    const gpu::ContextOptions gpu = options.gpu;
    benchmark::RegisterBenchmark("exam/extended/healthy/frames-10", [gpu](benchmark::State& s) { exam_row(s, gpu, 10.0); })
        ->Iterations(1)
        ->Unit(benchmark::kSecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark("exam/extended/healthy/stations-only", [gpu](benchmark::State& s) { exam_row(s, gpu, 0.0); })
        ->Iterations(1)
        ->Unit(benchmark::kSecond)
        ->UseRealTime();
    return nullptr;
}

}  // namespace echosim::bench

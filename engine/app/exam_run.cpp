#include "app/exam_run.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/exam_observers.hpp"
#include "app/stop_signals.hpp"
#include "exam/course_truth.hpp"
#include "io/partial_file.hpp"
#include "runner/exam_config.hpp"
#include "scene/leg.hpp"
#include "trainer/exam_files.hpp"

namespace echosim::app {
namespace {

std::string read_text(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::invalid_argument(file.string() + ": cannot be read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

PreparedExam prepare_exam(const std::filesystem::path& scenario_file, const std::string& case_id, std::uint64_t seed,
                          const std::filesystem::path& script)
{
    PreparedExam p;
    if (!scenario_file.empty()) p.scenario = exam::read_scenario(scenario_file);
    else if (case_id == "random") p.scenario = exam::read_scenario(exam::random_case(seed));
    else p.scenario = exam::read_scenario(exam::shipped_case(case_id.empty() ? "healthy" : case_id));
    const scene::LegModel leg;
    const echo::Phantom phantom(leg, p.scenario.anatomy);
    p.truth = exam::station_truth(phantom, p.scenario);
    const std::filesystem::path file = script.empty() ? exam::shipped_trajectory(p.scenario.id, "correct") : script;
    p.trajectory_name = file.string();
    const exam::SplitScript split = exam::split_exam_script(read_text(file), p.trajectory_name);
    p.trajectory = device::Trajectory::parse(split.trajectory_csv, p.trajectory_name);
    p.calls = split.calls;
    return p;
}

ExamRunResult perform_exam(const PreparedExam& exam, const VolumePair& volumes, const ExamRunOptions& options)
{
    ExamRunResult result;
    std::filesystem::create_directories(options.out / "stations");
    exam::Scorer scorer(exam.scenario, exam.truth);
    auto scoring = std::make_shared<ScorerObserver>(scorer, exam.calls);
    echo::PatientCase patient;
    patient.venous_pressure_mmHg = exam.scenario.patient.venous_pressure_mmHg;
    patient.heart_rate_bpm = exam.scenario.patient.heart_rate_bpm;

    // the exam, step by step on simulated time
    const auto run_start = std::chrono::steady_clock::now();
    {
        runner::ExamOptions o;
        o.session.patient = patient;
        // the exam window follows the lifted probe from the groin to the popliteal fossa
        o.session.window_follows_probe = true;
        o.volume = volumes.volume;
        o.labels = volumes.labels;
        o.imaging = options.imaging ? options.imaging : exam.scenario.imaging;
        // no frames written: nothing asks the runner for one, so it makes none (no volume on the
        // GPU: the stations' images are the CPU twin's, below), and the imaging the frames would
        // have had is the device's choice all the same
        o.draws = options.frames_per_s != 0;
        if (!o.draws && !o.imaging) o.imaging = runner::default_imaging(gpu::Context(options.gpu), volumes.labels.get());
        o.trajectory = exam.trajectory;
        o.trajectory_name = exam.trajectory_name;
        o.frames_per_s = options.frames_per_s;
        o.frames_dir = options.out / "frames";
        o.gpu = options.gpu;
        o.observers.push_back(scoring);
        runner::Runner runner(runner::exam_config(std::move(o)));
        const auto messages = runner.validation_counter();
        while (!(options.stop && options.stop->requested()) && runner.step()) {
        }
        runner.finish();
        result.steps = runner.steps();
        result.frames = runner.frames();
        result.simulated_s = runner.session().time();
        result.validation_messages = messages ? messages->load() : 0;
        result.imaging = runner.imaging();
    }
    result.run_wall_s = seconds_since(run_start);
    if (options.stop && options.stop->requested()) {
        result.stopped = true;
        return result;
    }

    // each station's deepest press imaged on the CPU twin: its picture and its deformed labels, the
    // report written (trainer/exam_files.hpp, shared with the trainer)
    const auto report_start = std::chrono::steady_clock::now();
    io::write_file<std::runtime_error>(options.out / "force.csv", scoring->force_csv());
    result.report = trainer::write_exam_report(scorer, *volumes.volume, volumes.labels.get(), patient, options.out, options.trainee, result.imaging);
    result.report_wall_s = seconds_since(report_start);
    return result;
}

}  // namespace echosim::app

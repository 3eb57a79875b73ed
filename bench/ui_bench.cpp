// Suite "ui": what the trainer's UI pass costs in a 1080p frame (issue 32, "Numbers": at most 10 %
// of a 1920x1080 frame on lavapipe), and the same frames at the 4K kiosk's 3840x2160 with its UI
// at twice the scale (the kiosk's frame rate: >= 60 fps on a real GPU; offscreen and each frame
// waited for, so a floor under what a window that keeps frames in flight presents). The runner as the trainer runs it (lock-step offscreen, the
// trainer's driver and its UI pass, the healthy case's coarse volume) on each of the trainer's
// screens: the start screen; the exam screen, the lesson started (the probe resting where the
// session puts it, off the stations); the report screen, that lesson ended after 3 s (every
// station skipped: the longest error list a report shows). On each screen the same runner draws
// frames with the UI pass shown and hidden (ui::UiPass::set_shown: hidden, it builds and draws
// nothing), in alternating blocks, so a shared machine's load falls on both alike.
//
// A frame's time: from the step's last observer (the frame asked for) to its on_frame, the frame
// recorded, submitted and waited for (runner/presenter.hpp: offscreen), the UI built in it; not
// the physics' step before it.
//
// Counters per screen: frame_ms_ui, frame_ms_bare (medians over kFrames each, after kWarmUp of
// each), ui_ms (their difference), ui_share (ui_ms over frame_ms_ui; the goal: at most 0.10), fps_ui
// (1000 over frame_ms_ui).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <vector>

#include <unistd.h>

#include "app/exam_run.hpp"
#include "app/exam_volume.hpp"
#include "bench/suites.hpp"
#include "exam/scenario.hpp"
#include "runner/exam_config.hpp"
#include "trainer/trainer_driver.hpp"

namespace echosim::bench {
namespace {

using Clock = std::chrono::steady_clock;

// the trainer's 1080p window (the goal's frame) and the 4K kiosk (its UI at the kiosk's scale)
struct Display {
    VkExtent2D extent;
    float ui_scale;
};
constexpr Display kDisplays[] = {{{1920, 1080}, 1.0f}, {{3840, 2160}, 2.0f}};
constexpr int kWarmUp = 5;   // frames of each kind first, not counted
constexpr int kFrames = 40;  // frames of each kind counted
constexpr int kBlock = 4;    // frames in a row of one kind

// Asks for every step's frame and times it (the last observer: its on_step comes just before).
class FrameTimer final : public runner::Observer {
public:
    void on_step(runner::StepContext& step) override
    {
        step.want_frame();
        started_ = Clock::now();
    }
    void on_frame(const runner::FrameContext& frame) override
    {
        if (frame.shown) last_ms = std::chrono::duration<double, std::milli>(Clock::now() - started_).count();
    }
    double last_ms = 0;

private:
    Clock::time_point started_;
};

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

void ui_row(benchmark::State& state, const gpu::ContextOptions& gpu, const app::PreparedExam& exam, const app::VolumePair& volumes,
            trainer::Screen screen, Display display)
{
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("echosim-bench-ui-" + std::to_string(::getpid()));
    for (auto _ : state) {
        std::filesystem::remove_all(dir);
        trainer::TrainerOptions to;
        to.cases = {exam::shipped_case("healthy")};
        to.records = dir / "records.sqlite";
        to.reports = dir / "reports";
        to.stamp_time = false;
        auto t = std::make_shared<trainer::Trainer>(to);
        t->form().trainee = "Bench Trainee";
        echo::PatientCase patient;
        patient.venous_pressure_mmHg = exam.scenario.patient.venous_pressure_mmHg;
        patient.heart_rate_bpm = exam.scenario.patient.heart_rate_bpm;
        trainer::DriverOptions driver_options{
            .frame_every_steps = 0, .loaded_case = "healthy", .volume = volumes.volume, .labels = volumes.labels, .patient = patient};
        // the kiosk's scale, as trainer_window.cpp makes it for a 4K monitor (its height over 1080)
        driver_options.ui_scale = [s = display.ui_scale]() { return s; };
        auto driver = std::make_shared<trainer::TrainerDriver>(t, driver_options);
        auto timer = std::make_shared<FrameTimer>();
        runner::ExamOptions o;
        o.session.patient = patient;
        o.session.window_follows_probe = true;
        o.volume = volumes.volume;
        o.labels = volumes.labels;
        o.duration_s = 3600;
        o.gpu = gpu;
        o.extent = display.extent;
        o.observers = {driver, timer};
        runner::RunnerConfig config = runner::exam_config(std::move(o));
        for (runner::PassFactory& f : driver->passes()) config.passes.push_back(std::move(f));
        runner::Runner r(std::move(config));

        // the screen: the lesson started for the exam, and for the report ended after 3 s of it
        if (screen != trainer::Screen::start) {
            t->start(r.session().time());
            for (int i = 0; i < (screen == trainer::Screen::report ? 180 : 10); ++i) r.step();
            if (screen == trainer::Screen::report) t->finish();
        }
        if (t->screen() != screen) {
            state.SkipWithError("the trainer is not on the screen asked for");
            break;
        }
        // frames with the UI and without, in alternating blocks
        std::vector<double> with, without;
        int warm_with = 0, warm_without = 0;
        for (int block = 0; int(with.size()) < kFrames || int(without.size()) < kFrames; ++block) {
            const bool shown = block % 2 == 0;
            driver->ui()->set_shown(shown);
            for (int i = 0; i < kBlock; ++i) {
                r.step();
                int& warm = shown ? warm_with : warm_without;
                std::vector<double>& into = shown ? with : without;
                if (warm < kWarmUp) ++warm;
                else if (int(into.size()) < kFrames) into.push_back(timer->last_ms);
            }
        }
        // which device drew it: the goals are lavapipe's (bench/goals.hpp, lavapipe_only)
        state.counters["cpu_device"] = r.context() && r.context()->device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 : 0;
        r.finish();
        const double ui = median(with), bare = median(without);
        state.counters["frame_ms_ui"] = ui;
        state.counters["frame_ms_bare"] = bare;
        state.counters["ui_ms"] = ui - bare;
        state.counters["ui_share"] = ui > 0 ? (ui - bare) / ui : 0;
        state.counters["fps_ui"] = ui > 0 ? 1000.0 / ui : 0;
        state.counters["frames"] = double(with.size() + without.size());
    }
    std::filesystem::remove_all(dir);
}

struct Shared {
    app::PreparedExam exam;
    app::VolumePair volumes;
};

}  // namespace

std::shared_ptr<void> register_ui(const SuiteOptions& options)
{
    const gpu::ContextOptions gpu = options.gpu;
    auto shared = std::make_shared<Shared>();
    shared->exam = app::prepare_exam({}, "healthy", 1, {});
    shared->volumes = app::exam_volume(shared->exam.scenario, true, gpu, {});
    for (const Display display : kDisplays)
        for (const trainer::Screen s : {trainer::Screen::start, trainer::Screen::exam, trainer::Screen::report}) {
            const std::string name = "ui/" + std::to_string(display.extent.width) + "x" + std::to_string(display.extent.height) + "/" +
                                     trainer::screen_name(s);
            const Shared* d = shared.get();
            benchmark::RegisterBenchmark(name.c_str(),
                                         [gpu, d, s, display](benchmark::State& st) { ui_row(st, gpu, d->exam, d->volumes, s, display); })
                ->Iterations(1)
                ->Unit(benchmark::kSecond)
                ->UseRealTime();
        }
    return shared;
}

}  // namespace echosim::bench

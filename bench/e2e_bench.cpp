// Suite "e2e": from a probe move to the echographic image that shows it being presented (issue 32,
// "Numbers"), in the simulator as a trainee runs it: the runner on the real-time clock, the physics
// and the haptic loop on their threads, a frame every step. A hand (a world-pose device the bench
// moves) steps the probe 6 mm along the thigh and back, every 0.25 s, pressed 3 mm in; after each
// move the bench counts the frames presented until the first one whose echographic image was made
// from the moved probe (its input's face within 0.1 mm of the new pose), and the milliseconds from
// the move to that frame's present. Rows: headless (offscreen) at 1280x720 and 1920x1080, and in a
// window at 1280x720 when there is a display (under `xvfb-run -s "-screen 0 1920x1080x24"` in CI).
//
// Counters: frames_p50/max (1: the first frame presented after the move shows it, the goal),
// latency_ms_p50/p95/max, frame_ms_p50 (the display's frame time meanwhile), moves.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "app/exam_run.hpp"
#include "app/exam_volume.hpp"
#include "bench/suites.hpp"
#include "device/held_device.hpp"
#include "runner/runner.hpp"
#include "scene/leg.hpp"

namespace echosim::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Watches for the first frame made from the moved probe after each move.
class MoveWatch final : public runner::Observer {
public:
    void moved(const glm::vec3& target)
    {
        target_ = target;
        moved_at_ = Clock::now();
        frames_since_ = 0;
        waiting_ = true;
    }
    void on_step(runner::StepContext& step) override
    {
        shows_move_ = waiting_ && glm::distance(step.view.echo->face.position, target_) < 0.1f;
    }
    void on_frame(const runner::FrameContext& frame) override
    {
        if (!frame.shown) return;
        const Clock::time_point now = Clock::now();
        if (last_frame_ != Clock::time_point{}) frame_ms.push_back(std::chrono::duration<double, std::milli>(now - last_frame_).count());
        last_frame_ = now;
        if (!waiting_) return;
        ++frames_since_;
        if (shows_move_) {
            frames.push_back(frames_since_);
            latency_ms.push_back(std::chrono::duration<double, std::milli>(now - moved_at_).count());
            waiting_ = false;
        }
    }
    bool waiting() const { return waiting_; }

    std::vector<double> frames, latency_ms, frame_ms;

private:
    glm::vec3 target_{0.0f};
    Clock::time_point moved_at_, last_frame_;
    int frames_since_ = 0;
    bool waiting_ = false, shows_move_ = false;
};

double quantile(std::vector<double> v, double q)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5))];
}

void e2e_row(benchmark::State& state, const gpu::ContextOptions& gpu, runner::Output output, VkExtent2D extent)
{
    const app::PreparedExam exam = app::prepare_exam({}, "healthy", 1, {});
    const app::VolumePair volumes = app::exam_volume(exam.scenario, true, gpu, {});
    const scene::LegModel leg;
    const Pose a = pressed_along_beam(leg.probe_rest_pose(0.5f, 0.5f), 3.0);
    Pose b = a;
    b.position += 6.0f * glm::normalize(leg.probe_rest_pose(0.55f, 0.5f).position - leg.probe_rest_pose(0.45f, 0.5f).position);
    for (auto _ : state) {
        auto hand = std::make_shared<device::HeldDevice>(a, "the e2e bench's hand");
        auto watch = std::make_shared<MoveWatch>();
        runner::RunnerConfig c;
        c.name = "e2e";
        c.session.clock = session::Clock::real_time;
        c.session.device = hand;
        c.session.haptics.realtime_priority = false;
        c.output = output;
        c.extent = extent;
        c.window = {int(extent.width), int(extent.height), false, "echosim bench e2e"};
        c.gpu = gpu;
        c.volume = volumes.volume;
        c.labels = volumes.labels;
        c.observers.push_back(watch);
        runner::Runner r(std::move(c));
        // 1 s to settle (pipelines compiled, the press made), then a move every 0.25 s for 6 s
        const Clock::time_point start = Clock::now();
        while (Clock::now() - start < std::chrono::seconds(1)) r.step();
        bool at_b = false;
        Clock::time_point next = Clock::now();
        while (Clock::now() - start < std::chrono::seconds(7)) {
            if (Clock::now() >= next && !watch->waiting()) {
                at_b = !at_b;
                const Pose& to = at_b ? b : a;
                hand->move_to(to);
                watch->moved(to.position);
                next = Clock::now() + std::chrono::milliseconds(250);
            }
            if (!r.step()) break;
        }
        // which device drew it: the goals are lavapipe's (bench/goals.hpp, lavapipe_only)
        state.counters["cpu_device"] = r.context() && r.context()->device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 : 0;
        r.finish();
        state.counters["moves"] = double(watch->latency_ms.size());
        state.counters["frames_p50"] = quantile(watch->frames, 0.5);
        state.counters["frames_max"] = quantile(watch->frames, 1.0);
        state.counters["latency_ms_p50"] = quantile(watch->latency_ms, 0.5);
        state.counters["latency_ms_p95"] = quantile(watch->latency_ms, 0.95);
        state.counters["latency_ms_max"] = quantile(watch->latency_ms, 1.0);
        state.counters["frame_ms_p50"] = quantile(watch->frame_ms, 0.5);
        if (watch->latency_ms.size() < 5) state.SkipWithError("fewer than 5 moves were seen in the image");
    }
}

}  // namespace

std::shared_ptr<void> register_e2e(const SuiteOptions& options)
{
    const gpu::ContextOptions gpu = options.gpu;
    for (const VkExtent2D e : {VkExtent2D{1280, 720}, VkExtent2D{1920, 1080}}) {
        const std::string name = "e2e/headless/" + std::to_string(e.width) + "x" + std::to_string(e.height);
        benchmark::RegisterBenchmark(name.c_str(), [gpu, e](benchmark::State& s) { e2e_row(s, gpu, runner::Output::offscreen, e); })
            ->Iterations(1)
            ->Unit(benchmark::kSecond)
            ->UseRealTime();
    }
    // a window only where there is a display to open it on
    if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY"))
        benchmark::RegisterBenchmark("e2e/window/1280x720",
                                     [gpu](benchmark::State& s) { e2e_row(s, gpu, runner::Output::window, {1280, 720}); })
            ->Iterations(1)
            ->Unit(benchmark::kSecond)
            ->UseRealTime();
    return nullptr;
}

}  // namespace echosim::bench

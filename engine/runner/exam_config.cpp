#include "runner/exam_config.hpp"

#include <cmath>
#include <stdexcept>

#include "device/scripted_device.hpp"
#include "runner/recorders.hpp"

namespace echosim::runner {

std::int64_t steps_covering(double duration_s, double dt_s) { return std::int64_t(std::ceil(duration_s / dt_s - 1e-6)); }

RunnerConfig exam_config(ExamOptions o)
{
    if (!(o.dt_s > 0) || !std::isfinite(o.dt_s)) throw std::invalid_argument("exam: dt_s " + std::to_string(o.dt_s) + " s: must be finite and > 0");
    double duration = o.duration_s;
    if (duration == 0 && o.trajectory) duration = o.trajectory->end_s();
    if (!(duration > 0) || !std::isfinite(duration))
        throw std::invalid_argument("exam: duration_s " + std::to_string(o.duration_s) + " s: must be finite and > 0" +
                                    (o.trajectory ? "" : " (there is no trajectory to take it from)"));
    if (o.frames_per_s != 0 && o.frames_dir.empty()) throw std::invalid_argument("exam: frames_per_s given without frames_dir");
    if (o.frames_per_s != 0 && !o.draws) throw std::invalid_argument("exam: frames_per_s given with draws false (no frame is made)");

    RunnerConfig c;
    c.name = "exam";
    c.session = std::move(o.session);
    c.session.clock = session::Clock::lock_step;
    if (o.trajectory)
        c.session.device = std::make_shared<device::ScriptedDevice>(std::move(*o.trajectory), o.trajectory_name, device::ScriptedDevice::Playback::once);
    c.lock_step_dt_s = o.dt_s;
    c.max_steps = steps_covering(duration, o.dt_s);
    c.output = o.draws ? Output::offscreen : Output::none;
    c.drawing = Drawing::on_request;
    c.gpu = std::move(o.gpu);
    c.extent = o.extent;
    c.volume = std::move(o.volume);
    c.labels = std::move(o.labels);
    c.imaging = o.imaging;
    if (o.frames_per_s != 0) c.observers.push_back(std::make_shared<FrameRecorder>(o.frames_dir, o.frames_per_s));
    for (auto& obs : o.observers) c.observers.push_back(std::move(obs));
    c.input = std::move(o.input);
    return c;
}

}  // namespace echosim::runner

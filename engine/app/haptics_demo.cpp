#include "app/haptics_demo.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "device/scripted_device.hpp"
#include "io/partial_file.hpp"
#include "io/plot.hpp"
#include "io/png.hpp"
#include "runner/runner.hpp"
#include "session/session.hpp"

namespace echosim::app {
namespace {

ForceCurveSummary summarise(const std::vector<ForceLogRow>& rows, double ForceLogRow::*force)
{
    ForceCurveSummary s;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const double before = rows[i - 1].*force, now = rows[i].*force;
        s.max_jump_N = std::max(s.max_jump_N, std::abs(now - before));
        if (rows[i].on_skin && rows[i - 1].on_skin && before > 0.0 && now <= 0.0) ++s.lost_contacts;
    }
    return s;
}

}  // namespace

namespace {

double script_end_s(const SlideScript& sc) { return 2.0 * (sc.approach_s + sc.hold_s) + sc.slide_s; }

// The script's poses every row_s from `t0` [s] on (its own time 0), appended to `rows`; the first
// one left out when it is already there (the end of the round before).
void append_slide_rows(const scene::LegModel& leg, const SlideScript& sc, double t0, bool skip_first, std::vector<device::TrajectoryRow>& rows)
{
    const double end = script_end_s(sc);
    // press along the beam over time: down from lift_mm above, hold, slide, hold, back up
    auto press_at = [&](double t) {
        const double down = -sc.lift_mm + (sc.press_mm + sc.lift_mm) * std::clamp(t / sc.approach_s, 0.0, 1.0);
        const double up = -sc.lift_mm + (sc.press_mm + sc.lift_mm) * std::clamp((end - t) / sc.approach_s, 0.0, 1.0);
        return std::min(down, up);
    };
    auto v_at = [&](double t) {
        const double s = std::clamp((t - sc.approach_s - sc.hold_s) / sc.slide_s, 0.0, 1.0);
        return sc.v_from + (sc.v_to - sc.v_from) * s;
    };
    for (long i = skip_first ? 1 : 0;; ++i) {
        const double t = std::min(double(i) * sc.row_s, end);
        const Pose p = pressed_along_beam(leg.probe_rest_pose(float(sc.u), float(v_at(t))), press_at(t));
        device::TrajectoryRow r;
        r.t_s = t0 + t;
        r.position = {p.position.x, p.position.y, p.position.z};
        r.orientation = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized();
        rows.push_back(r);
        if (t >= end) break;
    }
}

}  // namespace

SlideTrajectory make_slide_trajectory(const scene::LegModel& leg, const SlideScript& sc)
{
    std::vector<device::TrajectoryRow> rows;
    append_slide_rows(leg, sc, 0.0, false, rows);
    SlideTrajectory out{device::Trajectory::parse(device::format_trajectory(rows), "the slide script"), 0, 0};
    // pressed at least 1 mm in: from (1 + lift) / (press + lift) of the way down to as far back up
    const double in = (1.0 + sc.lift_mm) / (sc.press_mm + sc.lift_mm) * sc.approach_s;
    out.on_skin_from_s = in;
    out.on_skin_to_s = script_end_s(sc) - in;
    return out;
}

double round_trip_s(const SlideScript& script) { return 2.0 * script_end_s(script); }

device::Trajectory make_round_trip_trajectory(const scene::LegModel& leg, const SlideScript& sc)
{
    std::vector<device::TrajectoryRow> rows;
    append_slide_rows(leg, sc, 0.0, false, rows);
    SlideScript back = sc;
    std::swap(back.v_from, back.v_to);
    append_slide_rows(leg, back, script_end_s(sc), true, rows);
    return device::Trajectory::parse(device::format_trajectory(rows), "the slide script, there and back");
}

namespace {

// The demo's observer: every step (one haptic tick) a row of the log, from the loop's latest tick.
class Fig8Log final : public runner::Observer {
public:
    Fig8Log(Fig8Result& r, const SlideTrajectory& slide) : r_(r), slide_(slide) {}
    void on_step(runner::StepContext& step) override
    {
        const haptics::HapticSample& h = step.session.haptic_loop()->latest();
        ForceLogRow row;
        row.t_s = h.time_s;
        row.local_model_N = h.force.along_N;
        row.held_physics_N = h.physics_force_N;
        row.physics_step = h.physics_step;
        row.on_skin = h.time_s >= slide_.on_skin_from_s && h.time_s <= slide_.on_skin_to_s;
        r_.rows.push_back(row);
    }

private:
    Fig8Result& r_;
    const SlideTrajectory& slide_;
};

}  // namespace

Fig8Result run_fig8(const SlideScript& script, double physics_hz, std::vector<std::shared_ptr<runner::Observer>> observers)
{
    if (!(physics_hz >= 10.0 && physics_hz <= 1000.0))
        throw std::invalid_argument("physics rate " + std::to_string(physics_hz) + " Hz: outside 10..1000");
    const scene::LegModel leg;  // the session's leg is made the same way
    const SlideTrajectory slide = make_slide_trajectory(leg, script);
    // the runner's configuration with no frame, lock-step, one step per haptic tick
    runner::RunnerConfig c;
    c.name = "haptics-demo";
    session::SessionOptions& o = c.session;
    o.clock = session::Clock::lock_step;
    // the physics refreshes the loop at physics_hz, stepping the tissue 1 ms at a time in between
    // (physics_options.hpp: one 10 ms step is not accurate enough for the stiff contact)
    o.physics.time_step = 1e-3;
    o.physics.steps_per_publish = int(std::max(1L, std::lround(1000.0 / physics_hz)));
    o.device = std::make_shared<device::ScriptedDevice>(slide.trajectory, "the slide script");
    const double period_s = 1.0 / o.haptics.rate_hz;  // the loop's (HapticLoop::period_s)
    c.lock_step_dt_s = period_s;
    c.max_steps = std::lround(slide.trajectory.end_s() / period_s);
    c.output = runner::Output::none;

    Fig8Result r;
    r.physics_hz = 1.0 / (o.physics.time_step * o.physics.steps_per_publish);
    r.haptic_hz = 1.0 / period_s;
    r.rows.reserve(std::size_t(c.max_steps));
    c.observers.push_back(std::make_shared<Fig8Log>(r, slide));
    for (auto& obs : observers) c.observers.push_back(std::move(obs));
    runner::Runner runner(std::move(c));
    runner.run();
    r.local_model = summarise(r.rows, &ForceLogRow::local_model_N);
    r.held_physics = summarise(r.rows, &ForceLogRow::held_physics_N);
    return r;
}

void write_fig8(const Fig8Result& r, const std::filesystem::path& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot make the folder: " + ec.message());

    const std::filesystem::path csv = dir / "force_log.csv";
    {
        std::string text = "t_s,local_model_N,held_physics_N,physics_step,on_skin\n";
        char line[160];
        for (const ForceLogRow& row : r.rows) {
            std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%lld,%d\n", row.t_s, row.local_model_N, row.held_physics_N, row.physics_step,
                          int(row.on_skin));
            text += line;
        }
        io::write_file<std::runtime_error>(csv, text);
    }

    io::Plot plot;
    plot.title = "Force on the probe sliding across the thigh (haptic loop 1 kHz, physics " + std::to_string(int(r.physics_hz)) + " Hz)";
    plot.x_label = "time [s]";
    plot.y_label = "force [N]";
    io::Series held{"without the local model (physics force held)", std::nullopt, {}, io::SeriesStyle::line};
    io::Series local{"with the local model", std::nullopt, {}, io::SeriesStyle::line};
    for (const ForceLogRow& row : r.rows) {
        held.points.push_back({row.t_s, row.held_physics_N});
        local.points.push_back({row.t_s, row.local_model_N});
    }
    plot.series = {std::move(held), std::move(local)};
    char note[200];
    std::snprintf(note, sizeof note, "largest jump in 1 ms: %.3f N with, %.3f N without\nlost contacts on the skin: %d with, %d without",
                  r.local_model.max_jump_N, r.held_physics.max_jump_N, r.local_model.lost_contacts, r.held_physics.lost_contacts);
    plot.annotation = note;
    io::write_png(dir / "force.png", io::render_plot(plot, 1600, 800));

    nlohmann::json j = {{"haptic_hz", r.haptic_hz},
                        {"physics_hz", r.physics_hz},
                        {"ticks", r.rows.size()},
                        {"local_model", {{"max_jump_N_per_ms", r.local_model.max_jump_N}, {"lost_contacts", r.local_model.lost_contacts}}},
                        {"held_physics", {{"max_jump_N_per_ms", r.held_physics.max_jump_N}, {"lost_contacts", r.held_physics.lost_contacts}}}};
    const std::filesystem::path summary = dir / "summary.json";
    io::write_file<std::runtime_error>(summary, j.dump(2) + "\n");
}

}  // namespace echosim::app

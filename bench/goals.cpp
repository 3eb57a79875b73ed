#include "bench/goals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace echosim::bench {
namespace {

// three significant figures, without an exponent for the figures a table shows
std::string number(double v)
{
    char text[32];
    const double a = std::abs(v);
    if (a >= 100)
        std::snprintf(text, sizeof text, "%.0f", v);
    else if (a >= 10)
        std::snprintf(text, sizeof text, "%.1f", v);
    else
        std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

const nlohmann::json* find_row(const nlohmann::json& report, const Goal& g)
{
    for (const nlohmann::json& suite : report) {
        if (suite.value("bench", "") != g.suite || !suite.contains("results")) continue;
        for (const nlohmann::json& row : suite["results"])
            if (row.value("name", "") == g.row) return &row;
    }
    return nullptr;
}

bool suite_ran(const nlohmann::json& report, const std::string& suite)
{
    return std::any_of(report.begin(), report.end(), [&](const nlohmann::json& s) { return s.value("bench", "") == suite; });
}

}  // namespace

const std::vector<Goal>& design_goals()
{
    using C = Compare;
    static const std::vector<Goal> goals = {
        {"fit error over all samples (shipped set, Levenberg-Marquardt)", "MAE 1.05 N, SD 0.84 N, about 5 %", "MAE <= 5 % of the mean force",
         "fit", "fit/levenberg-marquardt", "rel_error", C::at_most, 0.05, 100, "%"},
        {"full fit time", "-", "< 5 s", "fit", "fit/levenberg-marquardt", "ms_per_iteration", C::at_most, 5000, 0.001, "s"},
        {"physics rate, 2,500 nodes, one core", "about 100 Hz (SGI R10000, ~64-node patch)", ">= 1 kHz with >= 2,000 nodes on one core",
         "physics", "physics/2500/implicit/updated", "steps_per_s", C::at_least, 1000, 1, "steps/s"},
        {"physics rate, 50,625 nodes, one core", "-", ">= 100 Hz with >= 50,000 nodes", "physics", "physics/50625/implicit/updated",
         "steps_per_s", C::at_least, 100, 1, "steps/s"},
        {"physics rate, 50,625 nodes, two threads", "-", ">= 100 Hz with >= 50,000 nodes", "physics",
         "physics/50625/implicit/updated/2threads", "steps_per_s", C::at_least, 100, 1, "steps/s"},
        {"haptic loop rate, physics and rendering running", "1 kHz", "1 kHz", "haptics", "haptics/loop/1000Hz/physics-2500/rendering",
         "rate_hz", C::at_least, 999, 1, "Hz"},
        {"haptic period error, p99", "-", "<= 0.1 ms while physics and rendering run", "haptics", "haptics/loop/1000Hz/physics-2500/rendering",
         "period_p99_err_ms", C::at_most, 0.1, 1, "ms"},
        {"haptic period error, max", "-", "no missed deadline > 1 ms", "haptics", "haptics/loop/1000Hz/physics-2500/rendering",
         "period_max_err_ms", C::at_most, 1.0, 1, "ms"},
        {"haptic loop's latest tick after its deadline, less cyclictest's latest wake-up beside it", "-",
         "<= 0: no later than the machine's own floor under the same load (issue 34)", "haptics", "haptics/loop/1000Hz/physics-2500/rendering",
         "late_over_cyclictest_ms", C::at_most, 0.0, 1, "ms"},
        {"haptic loop's page faults after its start", "-", "none (issue 34)", "haptics", "haptics/loop/1000Hz/physics-2500/rendering",
         "page_faults", C::at_most, 0.0, 1, ""},
        {"image: slice + deform + post, 1024x1024, 0.3 mm volume, lavapipe", "\"real time\" from a 0.3 mm, 120 MB voxel map",
         ">= 130 fps on lavapipe (2 CPU cores): vtkImageReslice's slicing alone, 97-136 fps on 2026-11-23's Xeon VM "
         "(bench/baselines/paired.sh: VTK in the same spell)",
         "slice", "slice/lavapipe/1024x1024/0.3mm", "fps", C::at_least, 130, 1, "fps"},
        {"image: slice + deform + post, 1024x1024, 0.1 mm volume (VTK's size), lavapipe", "-",
         ">= 130 fps on lavapipe: vtkImageReslice's slicing alone, 97-136 fps (paired.sh: VTK in the same spell)",
         "slice", "slice/lavapipe/1024x1024/0.1mm", "fps",
         C::at_least, 130, 1, "fps"},
        {"image: slice alone (a pressed frame's warped sampling), 1024x1024, 0.3 mm volume, lavapipe", "-",
         ">= 250 fps on lavapipe: twice vtkImageReslice's (paired.sh: VTK in the same spell)",
         "slice", "slice-only/lavapipe/1024x1024/0.3mm", "fps", C::at_least, 250, 1, "fps"},
        {"image: slice alone (a pressed frame's warped sampling), 1024x1024, 0.1 mm volume, lavapipe", "-",
         ">= 250 fps on lavapipe: twice vtkImageReslice's (paired.sh: VTK in the same spell)",
         "slice", "slice-only/lavapipe/1024x1024/0.1mm", "fps", C::at_least, 250, 1, "fps"},
        {"image: slice + deform + post, 1024x1024, 0.3 mm volume, real GPU", "-", ">= 1,000 fps on a real GPU", "slice",
         "slice/gpu/1024x1024/0.3mm", "fps", C::at_least, 1000, 1, "fps", "no GPU"},
        {"reconstruction: frames inserted, 640x480", "offline", ">= 30 frames/s (faster than acquisition)", "reconstruct", "reconstruct/0.3mm",
         "frames_per_s", C::at_least, 30, 1, "frames/s"},
        {"reconstruction: hole filling, 0.3 mm volume", "offline", "hole-filled volume in < 30 s", "reconstruct", "reconstruct/0.3mm",
         "fill_seconds", C::at_most, 30, 1, "s"},
        {"reconstruction: hole filling, 0.1 mm volume (native voxels)", "-", "volumes at native 0.1 mm voxels work (< 30 s)", "reconstruct",
         "reconstruct/0.1mm", "fill_seconds", C::at_most, 30, 1, "s"},
        // B-mode synthesis (issue 33)
        {"B-mode sweep synthesis, 400x500, lavapipe", "-", ">= 50 frames/s: a case's volume in under 10 s (issue 33)", "bmode",
         "bmode/lavapipe/400x500", "fps", C::at_least, 50, 1, "frames/s"},
        {"the live generative image, pressed (deform included), 512x512, lavapipe", "-", ">= 30 fps (issue 33)", "bmode",
         "bmode/lavapipe/512x512/live", "fps", C::at_least, 30, 1, "fps"},
        {"the live generative image, pressed (deform included), 1024x1024, real GPU", "-", ">= 1,000 fps on a real GPU (issue 33)", "bmode",
         "bmode/gpu/1024x1024/live", "fps", C::at_least, 1000, 1, "fps", "no GPU"},
        // the exam and the trainer (issues 31 and 32)
        {"the extended exam headless, frames written at 10 per simulated second, lavapipe", "-", ">= real time (issue 31)", "exam",
         "exam/extended/healthy/frames-10", "realtime_x", C::at_least, 1, 1, "x real time"},
        {"the extended exam headless, images at the stations only, lavapipe", "-", ">= 5x real time (issue 31)", "exam",
         "exam/extended/healthy/stations-only", "realtime_x", C::at_least, 5, 1, "x real time"},
        {"a probe move to the presented image showing it, headless 1920x1080, lavapipe", "-", "within one displayed frame (issue 32)", "e2e",
         "e2e/headless/1920x1080", "frames_p50", C::at_most, 1, 1, "frames", "row not run", true},
        {"a probe move to the presented image showing it, a window (Xvfb) 1280x720, lavapipe", "-", "within one displayed frame (issue 32)",
         "e2e", "e2e/window/1280x720", "frames_p50", C::at_most, 1, 1, "frames", "no display: run under xvfb-run", true},
        {"the trainer's UI pass, exam screen, 1920x1080, lavapipe", "-", "<= 10 % of the frame (issue 32)", "ui", "ui/1920x1080/exam",
         "ui_share", C::at_most, 0.10, 100, "%", "row not run", true},
        {"the trainer's UI pass, report screen, 1920x1080, lavapipe", "-", "<= 10 % of the frame (issue 32)", "ui", "ui/1920x1080/report",
         "ui_share", C::at_most, 0.10, 100, "%", "row not run", true},
    };
    return goals;
}

const char* to_string(GoalStatus status)
{
    switch (status) {
    case GoalStatus::met: return "yes";
    case GoalStatus::not_met: return "no";
    case GoalStatus::not_measured: return "not measured";
    }
    return "?";
}

std::vector<GoalLine> evaluate_goals(std::span<const Goal> goals, const nlohmann::json& report)
{
    std::vector<GoalLine> lines;
    for (const Goal& g : goals) {
        if (!suite_ran(report, g.suite)) continue;
        GoalLine line{&g, GoalStatus::not_measured, 0, "not measured (" + g.missing + ")"};
        const nlohmann::json* row = find_row(report, g);
        if (row && g.lavapipe_only && row->contains("cpu_device") && (*row)["cpu_device"] == 0) {
            line.measured = "not measured (ran on a GPU, not lavapipe)";
        } else if (row && row->contains(g.field) && (*row)[g.field].is_number()) {
            line.value = (*row)[g.field].get<double>();
            const bool met = g.compare == Compare::at_least ? line.value >= g.threshold : line.value <= g.threshold;
            line.status = met ? GoalStatus::met : GoalStatus::not_met;
            line.measured = number(line.value * g.scale) + (g.unit.empty() ? "" : " " + g.unit);
            // a median of repetitions carries its spread (median_row): said beside the figure
            const std::string lo = g.field + "_min", hi = g.field + "_max";
            if (row->contains("repetitions") && row->contains(lo) && row->contains(hi) && (*row)[lo].is_number() && (*row)[hi].is_number())
                line.measured += " (median of " + std::to_string((*row)["repetitions"].get<long long>()) + ": " +
                                 number((*row)[lo].get<double>() * g.scale) + "-" + number((*row)[hi].get<double>() * g.scale) + ")";
        } else if (row) {
            line.measured = "not measured (no " + g.field + " in " + g.row + ")";
        }
        lines.push_back(std::move(line));
    }
    return lines;
}

std::string goal_table(std::span<const GoalLine> lines)
{
    std::string out = "| what | the paper (2005) | our goal | measured | met? |\n|---|---|---|---|---|\n";
    for (const GoalLine& l : lines)
        out += "| " + l.goal->what + " | " + l.goal->paper + " | " + l.goal->goal + " | " + l.measured + " | " + to_string(l.status) + " |\n";
    return out;
}

nlohmann::json goal_lines_json(std::span<const GoalLine> lines, const std::string& suite)
{
    nlohmann::json out = nlohmann::json::array();
    for (const GoalLine& l : lines) {
        if (l.goal->suite != suite) continue;
        out.push_back({{"what", l.goal->what},
                       {"paper", l.goal->paper},
                       {"goal", l.goal->goal},
                       {"row", l.goal->row},
                       {"field", l.goal->field},
                       {"compare", l.goal->compare == Compare::at_least ? ">=" : "<="},
                       {"threshold", l.goal->threshold},
                       {"value", l.status == GoalStatus::not_measured ? nlohmann::json(nullptr) : nlohmann::json(l.value)},
                       {"measured", l.measured},
                       {"met", to_string(l.status)}});
    }
    return out;
}

}  // namespace echosim::bench

#include "exam/exam_script.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/parse_number.hpp"
#include "core/printable_text.hpp"

namespace echosim::exam {
namespace {

constexpr const char* kTrajectoryHeader = "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz";  // device::Trajectory::kHeader
constexpr int kPoseFields = 8;

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

// the position of the n-th comma (0-based), or npos
std::size_t nth_comma(std::string_view s, int n)
{
    std::size_t at = std::string_view::npos;
    for (int i = 0; i <= n; ++i) {
        at = s.find(',', at == std::string_view::npos ? 0 : at + 1);
        if (at == std::string_view::npos) return at;
    }
    return at;
}

}  // namespace

SplitScript split_exam_script(const std::string& text, const std::string& source)
{
    SplitScript out;
    std::istringstream in(text);
    std::string line;
    int line_no = 0;
    bool header_seen = false, with_calls = false;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string_view l = trim(line);
        if (l.empty() || l.front() == '#') {
            out.trajectory_csv += line + "\n";
            continue;
        }
        if (!header_seen) {
            header_seen = true;
            std::string squeezed;
            for (char c : l)
                if (c != ' ' && c != '\t') squeezed += c;
            with_calls = squeezed == std::string(kTrajectoryHeader) + ",call";
            out.trajectory_csv += (with_calls ? std::string(kTrajectoryHeader) : line) + "\n";
            continue;
        }
        const std::size_t comma = with_calls ? nth_comma(l, kPoseFields - 1) : std::string_view::npos;
        if (comma == std::string_view::npos) {
            // no call column (or a row too short: the trajectory's reader names the missing field)
            out.trajectory_csv += line + "\n";
            continue;
        }
        out.trajectory_csv += std::string(l.substr(0, comma)) + "\n";
        const std::string_view call = trim(l.substr(comma + 1));
        if (call.empty()) continue;
        const std::string where = source + ":" + std::to_string(line_no);
        TimedCall c;
        if (call == call_name(Call::compressible))
            c.call = Call::compressible;
        else if (call == call_name(Call::not_compressible))
            c.call = Call::not_compressible;
        else
            throw std::invalid_argument(where + ": call '" + printable(call) + "' is not one of compressible, not-compressible (or empty)");
        const std::string_view t = trim(l.substr(0, l.find(',')));
        if (!parse_number(t, c.t_s) || !std::isfinite(c.t_s))
            throw std::invalid_argument(where + ": t_s '" + printable(t) + "' is not a finite number");
        out.calls.push_back(c);
    }
    return out;
}

std::string format_exam_script(const ExamScript& script)
{
    std::string text = std::string(kTrajectoryHeader) + ",call\n";
    std::size_t next_call = 0;
    char row[320];
    for (const ScriptedPose& p : script.poses) {
        const glm::quat q = p.pose.orientation;
        std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,", p.t_s, double(p.pose.position.x),
                      double(p.pose.position.y), double(p.pose.position.z), double(q.w), double(q.x), double(q.y), double(q.z));
        text += row;
        // a call rides on the row at its time
        if (next_call < script.calls.size() && script.calls[next_call].t_s <= p.t_s) text += call_name(script.calls[next_call++].call);
        text += "\n";
    }
    return text;
}

const char* plan_error_name(PlanError e)
{
    switch (e) {
    case PlanError::none: return "correct";
    case PlanError::skip: return "skip";
    case PlanError::light_press: return "light-press";
    case PlanError::oblique: return "oblique";
    case PlanError::artery: return "artery";
    case PlanError::excessive: return "excessive";
    case PlanError::mimic_called: return "mimic-called";
    }
    return "?";
}

Pose tilted_about_array(const Pose& rest, double deg)
{
    Pose p = rest;
    p.orientation = rest.orientation * glm::angleAxis(float(deg * std::numbers::pi / 180.0), glm::vec3(1, 0, 0));
    return p;
}

bool turns_far(const Pose& from, const Pose& to, const PlanOptions& o)
{
    const double cosine = glm::dot(from.axis_y(), to.axis_y());
    return cosine < std::cos(o.far_turn_deg * std::numbers::pi / 180.0);
}

ExamScript plan_exam(const std::vector<StationTruth>& stations, const std::vector<double>& press_mm, const PlanOptions& o)
{
    if (press_mm.size() != stations.size()) throw std::invalid_argument("plan_exam: one press depth per station");
    ExamScript script;
    double t = 0;
    auto at = [&](double dt, const Pose& pose) {
        t += dt;
        script.poses.push_back({t, pose});
    };
    bool first = true;
    Pose previous;
    for (std::size_t i = 0; i < stations.size(); ++i) {
        const bool here = i == o.at && o.error != PlanError::none;
        if (here && o.error == PlanError::skip) continue;
        const StationTruth& s = stations[i];
        Pose rest = s.ideal_probe;
        double depth = press_mm[i];
        if (here && o.error == PlanError::artery) {
            // slide along the array until the artery is under the beam's centre line
            const glm::vec3 x = rest.axis_x();
            const float shift = float(glm::dot(glm::vec3(s.artery.centre) - rest.position, x));
            rest.position += shift * x;
        }
        if (here && o.error == PlanError::oblique) {
            rest = tilted_about_array(rest, o.oblique_deg);
            if (o.oblique_press_mm >= 0) depth = o.oblique_press_mm;
        }
        if (here && o.error == PlanError::light_press) depth *= o.light_fraction;
        if (here && o.error == PlanError::excessive) depth = o.excessive_press_mm >= 0 ? o.excessive_press_mm : depth * o.excessive_factor;
        const Pose lifted = pressed_along_beam(rest, -o.lift_mm);
        if (first) {
            script.poses.push_back({0.0, lifted});
            first = false;
        } else if (turns_far(previous, rest, o)) {
            // round the limb, not through it: out along the last station's beam, across, and in
            const Pose out = pressed_along_beam(previous, -o.far_lift_mm), over = pressed_along_beam(rest, -o.far_lift_mm);
            at(o.travel_s, out);
            at(std::max(o.travel_s, double(glm::length(over.position - out.position)) / o.far_speed_mm_s), over);
            at(o.lower_s, lifted);
        } else {
            at(o.travel_s, lifted);
        }
        previous = rest;
        at(o.lower_s, rest);
        at(o.press_s, pressed_along_beam(rest, depth));
        at(o.hold_s, pressed_along_beam(rest, depth));
        Call call = s.thrombosed ? Call::not_compressible : Call::compressible;
        if (here && o.error == PlanError::mimic_called) call = Call::not_compressible;
        // a light press sees a vein that does not close: the classic false positive
        if (here && o.error == PlanError::light_press && !s.thrombosed) call = Call::not_compressible;
        script.calls.push_back({t, call});
        at(o.release_s, rest);
        at(o.lower_s, lifted);
    }
    return script;
}

}  // namespace echosim::exam

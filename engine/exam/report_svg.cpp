#include "exam/report_svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "io/plot.hpp"

namespace echosim::exam {
namespace {

std::string num(double v) { return fixed(v, 1); }

struct Xy {
    double x = 0, y = 0;
};

// ---- the force trace ------------------------------------------------------------------------

// The trace thinned to at most two samples a pixel column (its least and greatest, in time order),
// so a 1 kHz log of a ten-minute exam draws as a few thousand points with every peak kept.
std::vector<std::pair<double, double>> thin(const std::vector<std::pair<double, double>>& trace, double t0, double t1, int columns)
{
    if (trace.size() <= std::size_t(2 * columns)) return trace;
    std::vector<std::pair<double, double>> out;
    out.reserve(std::size_t(2 * columns));
    std::size_t i = 0;
    for (int c = 0; c < columns && i < trace.size(); ++c) {
        const double end = t0 + (t1 - t0) * (c + 1) / columns;
        std::size_t lo = i, hi = i;
        std::size_t k = i;
        for (; k < trace.size() && (trace[k].first < end || c == columns - 1); ++k) {
            if (trace[k].second < trace[lo].second) lo = k;
            if (trace[k].second > trace[hi].second) hi = k;
        }
        if (k == i) continue;  // no sample in this column
        out.push_back(trace[std::min(lo, hi)]);
        if (lo != hi) out.push_back(trace[std::max(lo, hi)]);
        i = k;
    }
    return out;
}

}  // namespace

const char* status_colour(StationStatus s)
{
    switch (s) {
    case StationStatus::covered: return "#2e7d32";
    case StationStatus::skipped: return "#9e9e9e";
    case StationStatus::wrong: return "#c62828";
    }
    return "#000000";
}

io::Rgba status_rgba(StationStatus s)
{
    const char* hex = status_colour(s);
    const auto v = [&](int i) { return std::uint8_t(std::stoi(std::string(hex + i, 2), nullptr, 16)); };
    return {v(1), v(3), v(5), 255};
}

std::string force_trace_svg(const ExamReport& report, int width, int height)
{
    const double left = 56, right = 16, top = 16, bottom = 40;
    const double pw = width - left - right, ph = height - top - bottom;

    // the ranges: the whole exam, and the largest of the forces and the bands
    double t1 = report.motion.duration_s, f1 = std::max(report.excessive_force_N * 1.15, report.adequate_force_N * 1.5);
    for (const auto& [t, f] : report.force_trace)
        if (std::isfinite(t) && std::isfinite(f)) t1 = std::max(t1, t), f1 = std::max(f1, f);
    for (const StationResult& s : report.stations) {
        t1 = std::max(t1, s.deepest_press_at_s);
        if (std::isfinite(s.peak_force_N)) f1 = std::max(f1, s.peak_force_N);
    }
    if (!(t1 > 0) || !std::isfinite(t1)) t1 = 1;
    if (!(f1 > 0) || !std::isfinite(f1)) f1 = 1;
    const std::vector<double> fticks = io::nice_ticks(0, f1 * 1.05, 6);
    if (!fticks.empty()) f1 = std::max(f1 * 1.05, fticks.back());
    const auto X = [&](double t) { return left + std::clamp(t / t1, 0.0, 1.0) * pw; };
    const auto Y = [&](double f) { return top + ph - std::clamp(f / f1, 0.0, 1.0) * ph; };

    std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"trace\" width=\"" + std::to_string(width) + "\" height=\"" +
                    std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
                    "\" role=\"img\" aria-label=\"probe force over time\">\n";
    // the adequate band and the excessive limit
    const double adequate = report.adequate_force_N, excessive = report.excessive_force_N;
    if (adequate > 0) {
        const double band_top = excessive > adequate ? excessive : f1;
        s += "<rect x=\"" + num(left) + "\" y=\"" + num(Y(band_top)) + "\" width=\"" + num(pw) + "\" height=\"" +
             num(Y(adequate) - Y(band_top)) + "\" fill=\"#e6f4e6\"/>\n";
        s += "<line x1=\"" + num(left) + "\" x2=\"" + num(left + pw) + "\" y1=\"" + num(Y(adequate)) + "\" y2=\"" + num(Y(adequate)) +
             "\" stroke=\"#2e7d32\" stroke-width=\"1\"/>\n";
        s += "<text x=\"" + num(left + pw - 4) + "\" y=\"" + num(Y(adequate) - 4) + "\" text-anchor=\"end\" fill=\"#2e7d32\">adequate from " +
             fixed(adequate, 1) + " N</text>\n";
    }
    if (excessive > 0) {
        s += "<line x1=\"" + num(left) + "\" x2=\"" + num(left + pw) + "\" y1=\"" + num(Y(excessive)) + "\" y2=\"" + num(Y(excessive)) +
             "\" stroke=\"#c62828\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>\n";
        s += "<text x=\"" + num(left + pw - 4) + "\" y=\"" + num(Y(excessive) - 4) + "\" text-anchor=\"end\" fill=\"#c62828\">excessive above " +
             fixed(excessive, 1) + " N</text>\n";
    }
    // axes and ticks
    s += "<g class=\"axes\" stroke=\"#444\" fill=\"none\"><rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(pw) +
         "\" height=\"" + num(ph) + "\"/></g>\n<g class=\"ticks\">\n";
    for (double f : fticks)
        s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(Y(f) + 4) + "\" text-anchor=\"end\">" + fixed(f, f1 < 5 ? 1 : 0) + "</text>\n";
    for (double t : io::nice_ticks(0, t1, 10))
        s += "<text x=\"" + num(X(t)) + "\" y=\"" + num(top + ph + 16) + "\" text-anchor=\"middle\">" + fixed(t, t1 < 5 ? 1 : 0) + "</text>\n";
    s += "<text x=\"" + num(left + pw / 2) + "\" y=\"" + num(height - 4.0) + "\" text-anchor=\"middle\">time [s]</text>\n";
    s += "<text transform=\"translate(14 " + num(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">force [N]</text>\n</g>\n";
    // the stations' deepest presses
    for (std::size_t i = 0; i < report.stations.size(); ++i) {
        const StationResult& st = report.stations[i];
        if (!(st.deepest_press_at_s >= 0) || !std::isfinite(st.deepest_press_at_s)) continue;
        const double x = X(st.deepest_press_at_s);
        s += "<line x1=\"" + num(x) + "\" x2=\"" + num(x) + "\" y1=\"" + num(top) + "\" y2=\"" + num(top + ph) +
             "\" stroke=\"#777\" stroke-dasharray=\"2 3\"/>\n";
        s += "<text class=\"station\" transform=\"translate(" + num(x - 3) + " " + num(top + 4) + ") rotate(-90)\" text-anchor=\"end\">" +
             html_escape(st.name) + "</text>\n";
    }
    // the trace
    const auto points = thin(report.force_trace, 0, t1, int(pw));
    std::string poly;
    for (const auto& [t, f] : points) {
        if (!std::isfinite(t) || !std::isfinite(f)) continue;
        if (!poly.empty()) poly += ' ';
        poly += num(X(t)) + "," + num(Y(f));
    }
    if (!poly.empty()) s += "<polyline fill=\"none\" stroke=\"#1565c0\" stroke-width=\"1.2\" points=\"" + poly + "\"/>\n";
    for (std::size_t i = 0; i < report.stations.size(); ++i) {
        const StationResult& st = report.stations[i];
        if (!(st.deepest_press_at_s >= 0) || !std::isfinite(st.deepest_press_at_s) || !std::isfinite(st.peak_force_N)) continue;
        s += "<circle cx=\"" + num(X(st.deepest_press_at_s)) + "\" cy=\"" + num(Y(st.peak_force_N)) + "\" r=\"4\" fill=\"" +
             status_colour(station_status(report, i)) + "\" stroke=\"#222\"><title>" + html_escape(st.name) + ": peak " +
             fixed(st.peak_force_N, 1) + " N at " + fixed(st.deepest_press_at_s, 1) + " s</title></circle>\n";
    }
    s += "</svg>\n";
    return s;
}

namespace {

// ---- the leg map ------------------------------------------------------------------------------

// A polyline and the point a fraction u of the way along it.
struct Path {
    std::vector<Xy> points;

    Xy at(double u) const
    {
        double total = 0;
        for (std::size_t i = 1; i < points.size(); ++i) total += std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
        double left = std::clamp(u, 0.0, 1.0) * total;
        for (std::size_t i = 1; i < points.size(); ++i) {
            const double len = std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
            if (left <= len && len > 0) {
                const double f = left / len;
                return {points[i - 1].x + f * (points[i].x - points[i - 1].x), points[i - 1].y + f * (points[i].y - points[i - 1].y)};
            }
            left -= len;
        }
        return points.back();
    }

    std::string svg_points() const
    {
        std::string out;
        for (const Xy& p : points) out += (out.empty() ? "" : " ") + num(p.x) + "," + num(p.y);
        return out;
    }
};

// the map's geometry [SVG px]: the deep vein down the middle, medial to the left
constexpr double kVeinX = 170, kTopY = 50, kBottomY = 570;
constexpr int kMapWidth = 360, kMapHeight = 660;

// Where the course's landmarks lie along the deep vein [cm]: the report's, else from its stations
// (a segment's end between its last station and the next segment's first), else typical
// proportions of a thigh's course (a schematic then, as the map says).
struct Course {
    double length = 0, sfj = 0, bifurcation = 0, hiatus = 0;
    std::map<std::string, double> branch_length;  // gsv, dfv: the farthest station's s along it
};

Course course_of(const ExamReport& r)
{
    std::map<std::string, std::pair<double, double>> span;  // segment -> least, greatest s_cm
    for (const StationResult& st : r.stations) {
        if (!std::isfinite(st.s_cm)) continue;
        auto [it, fresh] = span.try_emplace(st.segment, st.s_cm, st.s_cm);
        if (!fresh) it->second = {std::min(it->second.first, st.s_cm), std::max(it->second.second, st.s_cm)};
    }
    const auto has = [&](const char* seg) { return span.count(seg) != 0; };
    Course c;
    double deepest = 0;
    for (const char* seg : {"cfv", "fv", "popliteal"})
        if (has(seg)) deepest = std::max(deepest, span[seg].second);
    c.length = r.course.trifurcation_cm > 0 ? r.course.trifurcation_cm : std::max(deepest * 1.1, 10.0);
    const auto between = [&](const char* above, const char* below, double typical) {
        if (has(above) && has(below) && span[above].second < span[below].first) return (span[above].second + span[below].first) / 2;
        if (has(below) && span[below].first < typical) return span[below].first * 0.8;
        if (has(above) && span[above].second > typical) return std::min(span[above].second * 1.1, c.length);
        return typical;
    };
    c.bifurcation = r.course.bifurcation_cm > 0 ? r.course.bifurcation_cm : between("cfv", "fv", 0.12 * c.length);
    c.hiatus = r.course.hiatus_cm > 0 ? r.course.hiatus_cm : between("fv", "popliteal", 0.75 * c.length);
    c.sfj = r.course.sfj_cm > 0 ? r.course.sfj_cm : c.bifurcation * 0.5;
    if (r.course.sfj_cm <= 0)
        for (const StationResult& st : r.stations)
            if (st.segment == "cfv" && station_type(st.name, st.segment) == "sfj" && std::isfinite(st.s_cm)) c.sfj = st.s_cm;
    for (const char* seg : {"gsv", "dfv"}) c.branch_length[seg] = has(seg) ? std::max(span[seg].second * 1.25, 1.0) : 1.0;
    return c;
}

double deep_y(const Course& c, double s_cm) { return kTopY + std::clamp(s_cm / c.length, 0.0, 1.0) * (kBottomY - kTopY); }

Path branch_path(const Course& c, const std::string& segment)
{
    if (segment == "gsv") {
        const double y = deep_y(c, c.sfj);
        return {{{kVeinX, y}, {95, y + 30}, {80, y + 105}, {72, kBottomY}}};
    }
    const double y = deep_y(c, c.bifurcation);
    return {{{kVeinX, y}, {235, y + 45}, {250, y + 150}}};
}

}  // namespace

std::string leg_map_svg(const ExamReport& report)
{
    const Course course = course_of(report);
    const double bif_y = deep_y(course, course.bifurcation), hiatus_y = deep_y(course, course.hiatus), sfj_y = deep_y(course, course.sfj);
    std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"legmap\" width=\"" + std::to_string(kMapWidth) + "\" height=\"" +
                    std::to_string(kMapHeight) + "\" viewBox=\"0 0 " + std::to_string(kMapWidth) + " " + std::to_string(kMapHeight) +
                    "\" role=\"img\" aria-label=\"leg map: the stations on the vein course\">\n";
    // the landmarks
    s += "<line x1=\"40\" x2=\"300\" y1=\"" + num(kTopY) + "\" y2=\"" + num(kTopY) + "\" stroke=\"#8d6e63\" stroke-width=\"3\"/>\n";
    s += "<text x=\"" + num(kVeinX) + "\" y=\"" + num(kTopY - 10) + "\" text-anchor=\"middle\" class=\"landmark\">inguinal ligament</text>\n";
    s += "<line x1=\"120\" x2=\"230\" y1=\"" + num(hiatus_y) + "\" y2=\"" + num(hiatus_y) + "\" stroke=\"#8d6e63\" stroke-dasharray=\"4 3\"/>\n";
    s += "<text x=\"236\" y=\"" + num(hiatus_y + 4) + "\" class=\"landmark\">adductor hiatus</text>\n";
    // the veins: branches first, so the deep vein is drawn over their junctions
    s += "<polyline fill=\"none\" stroke=\"#90caf9\" stroke-width=\"7\" stroke-linecap=\"round\" points=\"" +
         branch_path(course, "gsv").svg_points() + "\"/>\n";
    s += "<polyline fill=\"none\" stroke=\"#90caf9\" stroke-width=\"8\" stroke-dasharray=\"10 5\" points=\"" +
         branch_path(course, "dfv").svg_points() + "\"/>\n";
    s += "<line x1=\"" + num(kVeinX) + "\" x2=\"" + num(kVeinX) + "\" y1=\"" + num(kTopY) + "\" y2=\"" + num(kBottomY) +
         "\" stroke=\"#64b5f6\" stroke-width=\"12\" stroke-linecap=\"round\"/>\n";
    s += "<g class=\"segment\" text-anchor=\"end\">";
    s += "<text x=\"152\" y=\"" + num((kTopY + bif_y) / 2 + 4) + "\">CFV</text>";
    s += "<text x=\"152\" y=\"" + num((bif_y + hiatus_y) / 2) + "\">FV</text>";
    s += "<text x=\"152\" y=\"" + num((hiatus_y + kBottomY) / 2) + "\">popliteal</text></g>\n";
    s += "<text x=\"62\" y=\"" + num(kBottomY - 40) + "\" text-anchor=\"end\" class=\"segment\" transform=\"rotate(-90 62 " +
         num(kBottomY - 40) + ")\">GSV</text>\n";
    s += "<text x=\"256\" y=\"" + num(bif_y + 150) + "\" class=\"segment\">DFV</text><text x=\"256\" y=\"" + num(bif_y + 164) +
         "\" class=\"landmark\">(deep)</text>\n";
    s += "<text x=\"96\" y=\"" + num(sfj_y + 16) + "\" text-anchor=\"end\" class=\"landmark\">SFJ</text>\n";
    s += "<text x=\"20\" y=\"595\" class=\"landmark\">medial</text><text x=\"" + std::to_string(kMapWidth - 20) +
         "\" y=\"595\" text-anchor=\"end\" class=\"landmark\">lateral</text>\n";

    // the stations: on the deep vein by their s, to scale; on a branch by their s along it
    for (std::size_t i = 0; i < report.stations.size(); ++i) {
        const StationResult& st = report.stations[i];
        const double sc = std::isfinite(st.s_cm) ? st.s_cm : 0;
        const bool branch = st.segment == "gsv" || st.segment == "dfv";
        const Xy p = branch ? branch_path(course, st.segment).at(sc / course.branch_length.at(st.segment)) : Xy{kVeinX, deep_y(course, sc)};
        const StationStatus status = station_status(report, i);
        s += "<g class=\"station\"><title>" + html_escape(st.name) + ": " + station_status_name(status) +
             (st.thrombosed ? ", thrombus" : "") + "</title>";
        if (st.thrombosed)
            s += "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"11\" fill=\"none\" stroke=\"#4e342e\" stroke-width=\"3\"/>";
        s += "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"7\" fill=\"" + status_colour(status) + "\" stroke=\"#222\"" +
             (status == StationStatus::skipped ? " stroke-dasharray=\"2 2\"" : "") + "/>";
        const bool left_side = st.segment == "gsv";
        s += "<text x=\"" + num(p.x + (left_side ? -14 : 14)) + "\" y=\"" + num(p.y + 4) + "\"" + (left_side ? " text-anchor=\"end\"" : "") +
             ">" + html_escape(st.name) + "</text></g>\n";
    }
    // the legend
    const std::array<StationStatus, 3> order{StationStatus::covered, StationStatus::skipped, StationStatus::wrong};
    for (std::size_t k = 0; k < order.size(); ++k) {
        const double x = 20 + 80.0 * double(k);
        s += "<circle cx=\"" + num(x) + "\" cy=\"620\" r=\"6\" fill=\"" + status_colour(order[k]) + "\" stroke=\"#222\"/><text x=\"" +
             num(x + 10) + "\" y=\"624\">" + station_status_name(order[k]) + "</text>\n";
    }
    s += "<circle cx=\"270\" cy=\"620\" r=\"8\" fill=\"none\" stroke=\"#4e342e\" stroke-width=\"3\"/><text x=\"282\" y=\"624\">clot</text>\n";
    s += std::string("<text x=\"") + num(kMapWidth / 2.0) + "\" y=\"650\" text-anchor=\"middle\" class=\"landmark\">" +
         (report.course.trifurcation_cm > 0 ? "the deep vein to scale" : "schematic: the landmarks placed from the stations") + "</text>\n";
    s += "</svg>\n";
    return s;
}

}  // namespace echosim::exam

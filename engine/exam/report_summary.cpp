#include "exam/report_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "exam/station_sheet.hpp"
#include "exam/report_svg.hpp"
#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "io/bitmap_font.hpp"
#include "io/plot.hpp"
#include "io/raster.hpp"

namespace echosim::exam {
namespace {

constexpr int kMargin = 24;                 // [px]
constexpr int kThumbWidth = 296;            // [px] five a row
constexpr int kThumbMaxHeight = 300;        // [px]
constexpr std::size_t kErrorsShown = 12;    // more are counted, not listed: the HTML lists them all
constexpr io::Rgba kInk{33, 33, 33, 255};
constexpr io::Rgba kGrey{117, 117, 117, 255};

// `text` broken at spaces into lines of at most `width` pixels.
std::vector<std::string> wrap(const std::string& text, int width, int scale)
{
    std::vector<std::string> lines;
    std::string line;
    std::size_t i = 0;
    while (i < text.size()) {
        const std::size_t end = std::min(text.find(' ', i), text.size());
        const std::string word = text.substr(i, end - i);
        const std::string candidate = line.empty() ? word : line + " " + word;
        if (!line.empty() && io::text_width(candidate, scale) > width) {
            lines.push_back(line);
            line = word;
        } else {
            line = candidate;
        }
        i = end + 1;
    }
    if (!line.empty()) lines.push_back(line);
    for (std::string& l : lines) l = io::fit_text(l, width, scale);
    return lines;
}

std::string format(const char* fmt, auto... args)
{
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}

io::Plot force_plot(const ExamReport& r)
{
    io::Plot plot;
    plot.title = "Probe force over the exam";
    plot.x_label = "time [s]";
    plot.y_label = "force [N]";
    plot.legend = io::Corner::top_left;
    plot.text_scale = 2;  // the page's own text size: the automatic one is for a plot alone
    double t1 = r.motion.duration_s;
    io::Series force{"force", io::Rgba{21, 101, 192, 255}, {}, io::SeriesStyle::line};
    for (const auto& [t, f] : r.force_trace) {
        force.points.push_back({t, f});
        if (std::isfinite(t)) t1 = std::max(t1, t);
    }
    if (!(t1 > 0)) t1 = 1;
    plot.x_range = io::Range{0, t1};
    plot.series.push_back(std::move(force));
    if (r.adequate_force_N > 0)
        plot.series.push_back({"adequate from " + fixed(r.adequate_force_N, 1) + " N", io::Rgba{46, 125, 50, 255},
                               {{0, r.adequate_force_N}, {t1, r.adequate_force_N}}, io::SeriesStyle::line});
    if (r.excessive_force_N > 0)
        plot.series.push_back({"excessive above " + fixed(r.excessive_force_N, 1) + " N", io::Rgba{198, 40, 40, 255},
                               {{0, r.excessive_force_N}, {t1, r.excessive_force_N}}, io::SeriesStyle::line});
    io::Series presses{"deepest press at a station", io::Rgba{0, 0, 0, 255}, {}, io::SeriesStyle::markers};
    for (const StationResult& s : r.stations)
        if (s.deepest_press_at_s >= 0) presses.points.push_back({s.deepest_press_at_s, s.peak_force_N});
    if (!presses.points.empty()) plot.series.push_back(std::move(presses));
    double f1 = std::max(r.excessive_force_N, r.adequate_force_N);
    for (const auto& [t, f] : r.force_trace)
        if (std::isfinite(f)) f1 = std::max(f1, f);
    plot.y_range = io::Range{0, f1 > 0 ? f1 * 1.15 : 1.0};
    return plot;
}

}  // namespace

io::RgbaImage report_summary(const ExamReport& r, const std::filesystem::path& dir)
{
    const int W = int(kSummaryWidth), text_w = W - 2 * kMargin;
    const io::RgbaImage plot = io::render_plot(force_plot(r), std::uint32_t(text_w), 400);

    // the thumbnails first: their sheet's height sets the page's
    SheetStyle sheet_style;
    sheet_style.width = text_w;
    sheet_style.thumb_width = kThumbWidth;
    sheet_style.thumb_max_height = kThumbMaxHeight;
    sheet_style.ink = kInk;
    sheet_style.muted = kGrey;
    const io::RgbaImage sheet = station_sheet(r, dir, sheet_style);
    const int line = 22;  // [px] a row of scale-2 text
    const std::size_t errors_listed = std::min(r.errors.size(), kErrorsShown);
    const int height = 250 + 410 + int(r.stations.size() + 3) * line + int(errors_listed + 4) * line + 3 * line +
                       int(sheet.height) + 40;

    io::RgbaImage img;
    img.width = std::uint32_t(W);
    img.height = std::uint32_t(height);
    img.pixels.assign(std::size_t(W) * std::size_t(height) * 4, 255);
    int y = kMargin;

    // the heading and the verdict
    io::draw_text(img, kMargin, y, io::fit_text("Exam report: " + r.case_title, text_w, 4), 4, kInk);
    y += 44;
    std::string facts = "Trainee: " + (r.trainee.empty() ? std::string("(unnamed)") : r.trainee) + "   Case: " + r.case_id +
                        "   Protocol: " + r.protocol;
    if (!r.started_utc.empty()) facts += "   Started: " + r.started_utc;
    io::draw_text(img, kMargin, y, io::fit_text(facts, text_w, 2), 2, kInk);
    y += 32;
    const io::Rgba verdict_colour = r.passed ? io::Rgba{27, 94, 32, 255} : io::Rgba{183, 28, 28, 255};
    const std::string verdict = "Score " + fixed(100 * r.score, 0) + " % (pass mark " + fixed(100 * r.pass_mark, 0) +
                                " %): " + (r.passed ? "PASSED" : "NOT PASSED");
    io::fill_rect(img, kMargin - 6, y - 6, io::text_width(verdict, 3) + 12, io::text_height(3) + 12,
         r.passed ? io::Rgba{232, 245, 233, 255} : io::Rgba{255, 235, 238, 255});
    io::draw_text(img, kMargin, y, verdict, 3, verdict_colour);
    y += 40;
    for (const std::string& l : wrap("Conclusion: " + r.conclusion, text_w, 2)) {
        io::draw_text(img, kMargin, y, l, 2, kInk);
        y += line;
    }
    io::draw_text(img, kMargin, y, r.dvt_present ? "The case: deep vein thrombosis present." : "The case: no deep vein thrombosis.", 2, kGrey);
    y += line + 12;

    // the force
    io::blit_scaled(img, plot, kMargin, y, int(plot.width), int(plot.height));
    y += int(plot.height) + 10;

    // the stations
    const std::string header = format("%-3s %-16s %-9s %6s  %-8s %7s %6s %9s %10s %-9s %-16s %-5s", "#", "station", "segment", "s[cm]",
                                      "status", "off[mm]", "angle", "peak[N]", "collapse", "truth", "call", "was");
    io::draw_text(img, kMargin + 20, y, header, 2, kGrey);
    y += line;
    for (std::size_t i = 0; i < r.stations.size(); ++i) {
        const StationResult& s = r.stations[i];
        const StationStatus status = station_status(r, i);
        // a station never reached has no press to measure
        const auto measured = [&](double v, int decimals) { return s.reached ? fixed(v, decimals) : std::string("-"); };
        io::fill_rect(img, kMargin, y + 1, 12, 12, status_rgba(status));
        const std::string row = format("%-3zu %-16.16s %-9.9s %6s  %-8s %7s %6s %9s %10s %-9s %-16s %-5s", i + 1, s.name.c_str(),
                                       s.segment.c_str(), fixed(s.s_cm, 1).c_str(), station_status_name(status), measured(s.offset_mm, 1).c_str(),
                                       measured(s.angle_deg, 1).c_str(), measured(s.peak_force_N, 1).c_str(), measured(s.collapse_ratio, 2).c_str(),
                                       s.thrombosed ? "thrombus" : "patent", call_name(s.call),
                                       s.call == Call::none ? "-" : s.call_correct ? "right" : "wrong");
        io::draw_text(img, kMargin + 20, y, io::fit_text(row, text_w - 20, 2), 2, kInk);
        y += line;
    }
    y += 10;

    // the errors, the motion
    io::draw_text(img, kMargin, y, r.errors.empty() ? "Flagged errors: none" : "Flagged errors: " + std::to_string(r.errors.size()), 2, kInk);
    y += line;
    for (std::size_t i = 0; i < errors_listed; ++i) {
        const FlaggedError& e = r.errors[i];
        const std::string text = format("%6s s  %-20s %-14s ", fixed(e.time_s, 1).c_str(), error_name(e.kind),
                                        e.station.empty() ? "(exam)" : e.station.c_str()) + e.detail;
        io::draw_text(img, kMargin + 20, y, io::fit_text(text, text_w - 20, 2), 2, io::Rgba{183, 28, 28, 255});
        y += line;
    }
    if (r.errors.size() > errors_listed) {
        io::draw_text(img, kMargin + 20, y, "... and " + std::to_string(r.errors.size() - errors_listed) + " more (report.html lists all)", 2, kGrey);
        y += line;
    }
    y += 10;
    const std::string motion = "Motion: " + fixed(r.motion.duration_s, 1) + " s, probe path " + fixed(r.motion.path_mm / 10, 1) +
                               " cm, angle from transverse mean " + fixed(r.motion.mean_angle_deg, 1) + " deg, largest " +
                               fixed(r.motion.max_angle_deg, 1) + " deg";
    io::draw_text(img, kMargin, y, io::fit_text(motion, text_w, 2), 2, kInk);
    y += line;
    const std::string osaus = "OSAUS (1-5): systematic examination " + fixed(r.osaus.systematic_examination, 1) + ", interpretation " +
                              fixed(r.osaus.interpretation, 1) + ", decision " + fixed(r.osaus.decision, 1);
    io::draw_text(img, kMargin, y, io::fit_text(osaus, text_w, 2), 2, kInk);
    y += line + 16;

    // the images at the deepest press
    if (sheet.height > 0) {
        io::blit_scaled(img, sheet, kMargin, y, int(sheet.width), int(sheet.height));
        y += int(sheet.height) + 16;
    }

    // the page ends under its content
    img.height = std::uint32_t(std::min(height, y + kMargin));
    img.pixels.resize(std::size_t(img.width) * img.height * 4);
    return img;
}

}  // namespace echosim::exam

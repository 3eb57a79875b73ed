#include "exam/report_html.hpp"

#include "exam/report_images.hpp"
#include "exam/report_svg.hpp"
#include "exam/report_text.hpp"
#include "exam/station_status.hpp"

namespace echosim::exam {
namespace {

constexpr const char* kStyle = R"(
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif; color: #212121; margin: 0 auto; max-width: 1400px; padding: 16px 24px; }
h1 { font-size: 24px; margin: 0 0 4px; } h2 { font-size: 18px; margin: 24px 0 8px; border-bottom: 1px solid #ddd; }
.case { font-size: 18px; margin: 0; } .id { color: #757575; }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 12px; margin: 8px 0; } dt { color: #616161; } dd { margin: 0; }
.verdict { display: inline-block; font-size: 20px; font-weight: 600; padding: 6px 14px; border-radius: 6px; margin: 6px 0; }
.pass { background: #e8f5e9; color: #1b5e20; border: 1px solid #a5d6a7; } .fail { background: #ffebee; color: #b71c1c; border: 1px solid #ef9a9a; }
.conclusion { font-size: 17px; }
.overview { display: flex; flex-wrap: wrap; gap: 24px; align-items: flex-start; }
svg { font: 12px system-ui, sans-serif; background: #fff; } svg .landmark { fill: #6d4c41; font-size: 11px; } svg .segment { font-weight: 600; fill: #0d47a1; }
svg .ticks text { fill: #424242; } svg text.station { font-size: 10px; fill: #424242; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; } th, td { padding: 4px 8px; border-bottom: 1px solid #e0e0e0; text-align: right; }
th { background: #f5f5f5; } td.text, th.text { text-align: left; }
.status { display: inline-block; width: 10px; height: 10px; border-radius: 50%; margin-right: 6px; border: 1px solid #222; }
tr.wrong td { background: #fff5f5; } tr.skipped td { color: #757575; }
.images { display: flex; flex-wrap: wrap; gap: 16px; } figure { margin: 0; max-width: 420px; } figure img { max-width: 100%; image-rendering: auto; border: 1px solid #bdbdbd; background: #000; }
figcaption { font-size: 13px; color: #424242; } .missing { padding: 24px; border: 1px dashed #bdbdbd; color: #757575; max-width: 380px; }
footer { margin-top: 32px; color: #757575; font-size: 12px; }
)";

std::string percent(double fraction) { return fixed(100.0 * fraction, 0) + " %"; }

std::string station_rows(const ExamReport& r)
{
    std::string s;
    for (std::size_t i = 0; i < r.stations.size(); ++i) {
        const StationResult& st = r.stations[i];
        const StationStatus status = station_status(r, i);
        s += std::string("<tr class=\"") + station_status_name(status) + "\">";
        s += "<td>" + std::to_string(i + 1) + "</td>";
        s += "<td class=\"text\">" + html_escape(st.name) + "</td>";
        s += "<td class=\"text\">" + html_escape(st.segment) + "</td>";
        s += "<td>" + fixed(st.s_cm, 1) + "</td>";
        s += "<td class=\"text\"><span class=\"status\" style=\"background:" + std::string(status_colour(status)) + "\"></span>" +
             station_status_name(status) + "</td>";
        s += "<td>" + (st.reached ? fixed(st.reached_at_s, 1) : std::string("-")) + "</td>";
        // a station never reached has no press to measure: its values would be the scorer's defaults
        const auto measured = [&](double v, int decimals) { return st.reached ? fixed(v, decimals) : std::string("-"); };
        s += "<td>" + measured(st.offset_mm, 1) + "</td>";
        s += "<td>" + measured(st.angle_deg, 1) + "</td>";
        s += "<td>" + measured(st.peak_force_N, 1) + "</td>";
        s += "<td>" + (st.reached ? fixed(st.lumen_rest_mm2, 1) + " &rarr; " + fixed(st.lumen_pressed_mm2, 1) : std::string("-")) + "</td>";
        s += "<td>" + measured(st.collapse_ratio, 2) + "</td>";
        s += "<td>" + measured(st.artery_area_ratio, 2) + "</td>";
        s += std::string("<td class=\"text\">") + (st.thrombosed ? "thrombus" : "patent") + "</td>";
        s += std::string("<td class=\"text\">") + call_name(st.call) + "</td>";
        s += std::string("<td class=\"text\">") + (st.call == Call::none ? "-" : st.call_correct ? "right" : "wrong") + "</td>";
        s += "</tr>\n";
    }
    return s;
}

std::string figures(const ExamReport& r, const std::filesystem::path& dir)
{
    std::string s;
    for (const StationResult& st : r.stations) {
        if (st.image_png.empty()) continue;
        const std::string caption = html_escape(st.name) + ": peak " + fixed(st.peak_force_N, 1) + " N, lumen " +
                                    fixed(st.lumen_pressed_mm2, 1) + " of " + fixed(st.lumen_rest_mm2, 1) + " mm&sup2; (ratio " +
                                    fixed(st.collapse_ratio, 2) + "), called " + call_name(st.call);
        const StationImage image = read_station_image(dir, st.image_png);
        s += "<figure>";
        if (image.png.empty())
            s += "<div class=\"missing\">" + html_escape(st.image_png) + ": " + html_escape(image.why) + "</div>";
        else
            s += "<img alt=\"" + html_escape(st.name) + " at its deepest press\" src=\"data:image/png;base64," + base64(image.png) + "\">";
        s += "<figcaption>" + caption + "</figcaption></figure>\n";
    }
    return s.empty() ? "<p>No images.</p>\n" : "<div class=\"images\">\n" + s + "</div>\n";
}

std::string error_rows(const ExamReport& r)
{
    if (r.errors.empty()) return "<p>None.</p>\n";
    std::string s = "<table><thead><tr><th class=\"text\">error</th><th class=\"text\">station</th><th>time [s]</th>"
                    "<th class=\"text\">detail</th></tr></thead><tbody>\n";
    for (const FlaggedError& e : r.errors)
        s += std::string("<tr><td class=\"text\">") + error_name(e.kind) + "</td><td class=\"text\">" +
             (e.station.empty() ? std::string("(whole exam)") : html_escape(e.station)) + "</td><td>" + fixed(e.time_s, 1) +
             "</td><td class=\"text\">" + html_escape(e.detail) + "</td></tr>\n";
    return s + "</tbody></table>\n";
}

}  // namespace

std::string report_html(const ExamReport& r, const std::filesystem::path& dir)
{
    const std::string trainee = r.trainee.empty() ? std::string("(unnamed)") : html_escape(r.trainee);
    std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    // no script at all, nothing fetched: the page is whole as written, and a string that slipped
    // past the escaping still could not run
    s += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; style-src 'unsafe-inline'\">\n";
    s += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    s += "<title>Exam report: " + trainee + ", " + html_escape(r.case_title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";

    s += "<header>\n<h1>Compression ultrasound exam</h1>\n";
    s += "<p class=\"case\">" + html_escape(r.case_title) + " <span class=\"id\">(" + html_escape(r.case_id) + ")</span></p>\n";
    s += "<dl class=\"facts\"><dt>Trainee</dt><dd>" + trainee + "</dd><dt>Protocol</dt><dd>" + html_escape(r.protocol) + "</dd>";
    if (!r.started_utc.empty()) s += "<dt>Started</dt><dd>" + html_escape(r.started_utc) + "</dd>";
    s += "<dt>Stations</dt><dd>" + std::to_string(r.stations.size()) + "</dd></dl>\n";
    s += std::string("<div class=\"verdict ") + (r.passed ? "pass" : "fail") + "\">Score " + percent(r.score) + " against a pass mark of " +
         percent(r.pass_mark) + ": " + (r.passed ? "passed" : "not passed") + "</div>\n";
    s += "<p class=\"conclusion\"><strong>Conclusion:</strong> " + html_escape(r.conclusion) + "</p>\n";
    s += std::string("<p>The case (the simulation's truth): ") + (r.dvt_present ? "deep vein thrombosis present" : "no deep vein thrombosis") +
         ".</p>\n</header>\n";

    s += "<section class=\"overview\">\n<div><h2>Leg map</h2>\n" + leg_map_svg(r) + "</div>\n";
    s += "<div><h2>Force over time</h2>\n" + force_trace_svg(r) + "<p>The probe's force; a dot at each station's deepest press, in its colour.";
    if (r.adequate_force_N > 0) s += " The shaded band: adequate pressure for this patient.";
    s += "</p></div>\n</section>\n";

    s += "<section><h2>Stations</h2>\n<table><thead><tr><th>#</th><th class=\"text\">station</th><th class=\"text\">segment</th>"
         "<th>s [cm]</th><th class=\"text\">status</th><th>reached [s]</th><th>offset [mm]</th><th>angle [&deg;]</th>"
         "<th>peak force [N]</th><th>lumen [mm&sup2;] rest &rarr; pressed</th><th>collapse ratio</th><th>artery ratio</th>"
         "<th class=\"text\">truth</th><th class=\"text\">call</th><th class=\"text\">call was</th></tr></thead><tbody>\n";
    s += station_rows(r) + "</tbody></table>\n</section>\n";

    s += "<section><h2>Images at maximum compression</h2>\n" + figures(r, dir) + "</section>\n";
    s += "<section><h2>Flagged errors</h2>\n" + error_rows(r) + "</section>\n";
    s += "<section><h2>Motion</h2>\n<dl class=\"facts\"><dt>Exam time</dt><dd>" + fixed(r.motion.duration_s, 1) +
         " s</dd><dt>Probe path</dt><dd>" + fixed(r.motion.path_mm / 10.0, 1) + " cm</dd><dt>Angle from transverse</dt><dd>mean " +
         fixed(r.motion.mean_angle_deg, 1) + "&deg;, largest " + fixed(r.motion.max_angle_deg, 1) + "&deg;</dd></dl>\n</section>\n";
    s += "<section><h2>OSAUS items</h2>\n<table><thead><tr><th class=\"text\">item</th><th>score (1&ndash;5)</th></tr></thead><tbody>\n"
         "<tr><td class=\"text\">Systematic examination</td><td>" + fixed(r.osaus.systematic_examination, 1) + "</td></tr>\n"
         "<tr><td class=\"text\">Interpretation of images</td><td>" + fixed(r.osaus.interpretation, 1) + "</td></tr>\n"
         "<tr><td class=\"text\">Medical decision making</td><td>" + fixed(r.osaus.decision, 1) + "</td></tr>\n</tbody></table>\n"
         "<p>Items of the Objective Structured Assessment of Ultrasound Skills (Tolsgaard et al. 2012).</p>\n</section>\n";
    s += "<footer>echosim: a simulated exam. The truth it is scored against is the simulation's, not a patient's.</footer>\n</body>\n</html>\n";
    return s;
}

}  // namespace echosim::exam

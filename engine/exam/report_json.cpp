#include "exam/report_json.hpp"

#include <cerrno>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>

#include <nlohmann/json.hpp>

#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "io/json_text.hpp"
#include "io/text_fields.hpp"

namespace echosim::exam {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written, not sorted: a person reads it

Json station_json(const ExamReport& report, std::size_t i)
{
    namespace d = report_decimals;
    const StationResult& s = report.stations[i];
    Json j;
    j["name"] = s.name;
    j["segment"] = s.segment;
    j["s_cm"] = rounded(s.s_cm, d::s_cm);
    j["status"] = station_status_name(station_status(report, i));
    j["reached"] = s.reached;
    j["reached_at_s"] = rounded(s.reached_at_s, d::time_s);
    j["offset_mm"] = rounded(s.offset_mm, d::length_mm);
    j["angle_deg"] = rounded(s.angle_deg, d::angle_deg);
    j["peak_force_N"] = rounded(s.peak_force_N, d::force_N);
    j["deepest_press_at_s"] = rounded(s.deepest_press_at_s, d::time_s);
    j["lumen_rest_mm2"] = rounded(s.lumen_rest_mm2, d::area_mm2);
    j["lumen_pressed_mm2"] = rounded(s.lumen_pressed_mm2, d::area_mm2);
    j["collapse_ratio"] = rounded(s.collapse_ratio, d::ratio);
    j["artery_area_ratio"] = rounded(s.artery_area_ratio, d::ratio);
    j["thrombosed"] = s.thrombosed;
    j["call"] = call_name(s.call);
    j["call_correct"] = s.call_correct;
    j["image_png"] = s.image_png;
    return j;
}

}  // namespace

std::string report_json(const ExamReport& report)
{
    namespace d = report_decimals;
    Json j;
    j["format"] = "echosim-exam-report";
    j["version"] = 1;
    j["trainee"] = report.trainee;
    j["case_id"] = report.case_id;
    j["case_title"] = report.case_title;
    j["protocol"] = report.protocol;
    j["started_utc"] = report.started_utc;
    j["score"] = rounded(report.score, d::score);
    j["pass_mark"] = rounded(report.pass_mark, d::score);
    j["passed"] = report.passed;
    j["conclusion"] = report.conclusion;
    j["dvt_present"] = report.dvt_present;
    j["adequate_force_N"] = rounded(report.adequate_force_N, d::force_N);
    j["excessive_force_N"] = rounded(report.excessive_force_N, d::force_N);
    Json stations = Json::array();
    for (std::size_t i = 0; i < report.stations.size(); ++i) stations.push_back(station_json(report, i));
    j["stations"] = std::move(stations);
    Json errors = Json::array();
    for (const FlaggedError& e : report.errors)
        errors.push_back(Json{{"kind", error_name(e.kind)}, {"station", e.station}, {"time_s", rounded(e.time_s, d::time_s)}, {"detail", e.detail}});
    j["errors"] = std::move(errors);
    j["motion"] = Json{{"duration_s", rounded(report.motion.duration_s, d::time_s)},
                       {"path_mm", rounded(report.motion.path_mm, d::length_mm)},
                       {"mean_angle_deg", rounded(report.motion.mean_angle_deg, d::angle_deg)},
                       {"max_angle_deg", rounded(report.motion.max_angle_deg, d::angle_deg)}};
    j["osaus"] = Json{{"systematic_examination", rounded(report.osaus.systematic_examination, d::osaus)},
                      {"interpretation", rounded(report.osaus.interpretation, d::osaus)},
                      {"decision", rounded(report.osaus.decision, d::osaus)}};
    // replace: a byte that is not UTF-8 becomes U+FFFD instead of an exception mid-report
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace echosim::exam

namespace echosim::exam {
namespace {

// Reads fields of one JSON object, naming the field's path in its errors.
class Fields {
public:
    Fields(const nlohmann::json& j, std::string where, const std::filesystem::path& file) : j_(j), where_(std::move(where)), file_(file)
    {
        if (!j.is_object()) fail("", "not an object");
    }

    const nlohmann::json& at(const char* key) const
    {
        const auto it = j_.find(key);
        if (it == j_.end()) fail(key, "missing");
        return *it;
    }
    std::string text(const char* key) const
    {
        const auto& v = at(key);
        if (!v.is_string()) fail(key, "not a string");
        return v.get<std::string>();
    }
    bool flag(const char* key) const
    {
        const auto& v = at(key);
        if (!v.is_boolean()) fail(key, "not true or false");
        return v.get<bool>();
    }
    double number(const char* key) const
    {
        const auto& v = at(key);
        if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();  // how a non-finite value is written
        if (!v.is_number()) fail(key, "not a number");
        return v.get<double>();
    }
    std::string path(const char* key) const { return where_ + "/" + key; }

    [[noreturn]] void fail(const std::string& key, const std::string& why) const
    {
        throw ReportError(file_.string() + ": field '" + (key.empty() ? (where_.empty() ? "/" : where_) : where_ + "/" + key) + "': " + why);
    }

private:
    const nlohmann::json& j_;
    std::string where_;
    const std::filesystem::path& file_;
};

}  // namespace

ExamReport parse_report_json(const std::string& text, const std::filesystem::path& file)
{
    nlohmann::json j;
    try {
        j = io::parse_json_text(text, io::JsonLimits{8, 256ull << 20});
    } catch (const io::JsonTextError& e) {
        throw ReportError(file.string() + ": " + e.what());
    }
    const Fields top(j, "", file);
    if (top.text("format") != "echosim-exam-report") top.fail("format", "not an echosim exam report");
    if (top.number("version") != 1) top.fail("version", "a report of a version this echosim cannot read");
    ExamReport r;
    r.trainee = top.text("trainee");
    r.case_id = top.text("case_id");
    r.case_title = top.text("case_title");
    r.protocol = top.text("protocol");
    r.started_utc = top.text("started_utc");
    r.score = top.number("score");
    r.pass_mark = top.number("pass_mark");
    r.passed = top.flag("passed");
    r.conclusion = top.text("conclusion");
    r.dvt_present = top.flag("dvt_present");
    r.adequate_force_N = top.number("adequate_force_N");
    r.excessive_force_N = top.number("excessive_force_N");

    const auto& stations = top.at("stations");
    if (!stations.is_array()) top.fail("stations", "not an array");
    for (std::size_t i = 0; i < stations.size(); ++i) {
        const Fields f(stations[i], "/stations/" + std::to_string(i), file);
        StationResult s;
        s.name = f.text("name");
        s.segment = f.text("segment");
        s.s_cm = f.number("s_cm");
        s.reached = f.flag("reached");
        s.reached_at_s = f.number("reached_at_s");
        s.offset_mm = f.number("offset_mm");
        s.angle_deg = f.number("angle_deg");
        s.peak_force_N = f.number("peak_force_N");
        s.deepest_press_at_s = f.number("deepest_press_at_s");
        s.lumen_rest_mm2 = f.number("lumen_rest_mm2");
        s.lumen_pressed_mm2 = f.number("lumen_pressed_mm2");
        s.collapse_ratio = f.number("collapse_ratio");
        s.artery_area_ratio = f.number("artery_area_ratio");
        s.thrombosed = f.flag("thrombosed");
        const std::string call = f.text("call");
        if (call == call_name(Call::none)) s.call = Call::none;
        else if (call == call_name(Call::compressible)) s.call = Call::compressible;
        else if (call == call_name(Call::not_compressible)) s.call = Call::not_compressible;
        else f.fail("call", "'" + call + "' is none of none, compressible, not-compressible");
        s.call_correct = f.flag("call_correct");
        s.image_png = f.text("image_png");
        r.stations.push_back(std::move(s));
    }
    const auto& errors = top.at("errors");
    if (!errors.is_array()) top.fail("errors", "not an array");
    for (std::size_t i = 0; i < errors.size(); ++i) {
        const Fields f(errors[i], "/errors/" + std::to_string(i), file);
        FlaggedError e;
        const std::string kind = f.text("kind");
        bool known = false;
        for (ErrorKind k : {ErrorKind::skipped_station, ErrorKind::too_little_pressure, ErrorKind::wrong_vessel, ErrorKind::oblique_plane,
                            ErrorKind::excessive_force, ErrorKind::mimic_called_clot, ErrorKind::wrong_call})
            if (kind == error_name(k)) e.kind = k, known = true;
        if (!known) f.fail("kind", "'" + kind + "' is not an error this echosim knows");
        e.station = f.text("station");
        e.time_s = f.number("time_s");
        e.detail = f.text("detail");
        r.errors.push_back(std::move(e));
    }
    const Fields motion(top.at("motion"), "/motion", file);
    r.motion = {motion.number("duration_s"), motion.number("path_mm"), motion.number("mean_angle_deg"), motion.number("max_angle_deg")};
    const Fields osaus(top.at("osaus"), "/osaus", file);
    r.osaus = {osaus.number("systematic_examination"), osaus.number("interpretation"), osaus.number("decision")};
    return r;
}

ExamReport read_report_json(const std::filesystem::path& file)
{
    if (io::text::is_special_file(file)) throw ReportError(file.string() + ": " + io::text::not_regular_file);
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ReportError(file.string() + ": cannot open: " + std::generic_category().message(errno));
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    constexpr std::uintmax_t kMost = 64u << 20;  // a report of thousands of stations is a few MB
    if (!ec && size > kMost) throw ReportError(file.string() + ": larger than 64 MiB: not an exam report");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return parse_report_json(text, file);
}

}  // namespace echosim::exam

#include "app/cmd_records.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "core/printable_text.hpp"
#include "exam/learning_curve.hpp"
#include "exam/records.hpp"
#include "exam/report_json.hpp"
#include "exam/report_text.hpp"
#include "exam/xapi.hpp"
#include "io/partial_file.hpp"

namespace echosim::app {
namespace {

using exam::fixed;

// The database named by --records, else the default; nullopt (said on stderr) when neither works.
std::optional<std::filesystem::path> records_path(const char* command, const RecordsArgs& args)
{
    if (!args.records.empty()) return args.records;
    try {
        return exam::default_records_path();
    } catch (const exam::RecordsError& e) {
        std::fprintf(stderr, "echosim %s: %s\n", command, e.what());
        return std::nullopt;
    }
}

std::string session_table(const std::vector<exam::SessionRecord>& sessions)
{
    std::string out = "    id  stored                trainee               case                        protocol     score  passed      time\n";
    char buf[512];
    for (const exam::SessionRecord& s : sessions) {
        std::snprintf(buf, sizeof buf, "  %4lld  %-20.20s  %-20.20s  %-26.26s  %-11.11s  %4s %%  %-6s  %7s s\n", static_cast<long long>(s.id),
                      printable(s.started_utc.empty() ? s.stored_utc : s.started_utc).c_str(), printable(s.trainee).c_str(),
                      printable(s.case_id).c_str(), printable(s.protocol).c_str(), fixed(100 * s.score, 0).c_str(), s.passed ? "yes" : "no",
                      fixed(s.duration_s, 1).c_str());
        out += buf;
    }
    return out;
}

// Text of several lines made safe for a terminal line by line (a trainee's name could hold an
// escape sequence), its newlines kept.
std::string printable_lines(const std::string& text)
{
    std::string out;
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        out += printable(std::string_view(text).substr(at, end - at));
        if (end < text.size()) out += '\n';
        at = end + 1;
    }
    return out;
}

// A double as JSON: null when not finite (JSON has no NaN).
nlohmann::ordered_json number(double v)
{
    return std::isfinite(v) ? nlohmann::ordered_json(exam::rounded(v, 4)) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json listing_json(const std::filesystem::path& path, const std::vector<exam::SessionRecord>& sessions,
                            const std::vector<exam::LearningCurve>& curves)
{
    nlohmann::ordered_json j;
    j["records"] = path.string();
    auto& list = j["sessions"] = nlohmann::ordered_json::array();
    for (const exam::SessionRecord& s : sessions)
        list.push_back({{"id", s.id}, {"trainee", s.trainee}, {"case_id", s.case_id}, {"case_title", s.case_title}, {"protocol", s.protocol},
                        {"started_utc", s.started_utc}, {"stored_utc", s.stored_utc}, {"score", number(s.score)}, {"passed", s.passed},
                        {"duration_s", number(s.duration_s)}});
    auto& out = j["learning_curves"] = nlohmann::ordered_json::array();
    for (const exam::LearningCurve& c : curves) {
        nlohmann::ordered_json curve;
        curve["trainee"] = c.trainee;
        curve["scores"] = nlohmann::ordered_json::array();
        for (const exam::SessionPoint& p : c.sessions) curve["scores"].push_back({{"session", p.session_id}, {"score", number(p.score)}});
        curve["cusum"] = {{"method", "Bolsin & Colson 2000 (Williams et al. 1992)"},
                          {"p0", c.parameters.p0}, {"p1", c.parameters.p1}, {"alpha", c.parameters.alpha}, {"beta", c.parameters.beta},
                          {"s", number(c.limits.s)}, {"h0", number(c.limits.h0)}, {"h1", number(c.limits.h1)}};
        auto& types = curve["station_types"] = nlohmann::ordered_json::array();
        for (const exam::StationTypeCurve& t : c.stations) {
            nlohmann::ordered_json sums = nlohmann::ordered_json::array();
            for (double v : t.cusum) sums.push_back(number(v));
            types.push_back({{"type", t.type}, {"successes", t.successes}, {"cusum", std::move(sums)},
                             {"verdict", exam::cusum_verdict_name(t.verdict)}});
        }
        out.push_back(std::move(curve));
    }
    return j;
}

}  // namespace

int run_records(const RecordsArgs& args)
{
    const auto path = records_path("records", args);
    if (!path) return kExitBadInput;
    if (!args.plot.empty() && !output_path_usable("records", "--plot", args.plot)) return kExitBadInput;
    std::error_code ec;
    if (!std::filesystem::exists(*path, ec)) {
        // nothing stored yet is no error where the records live by default; a named file that is
        // not there is a mistyped path
        if (!args.records.empty()) {
            std::fprintf(stderr, "echosim records: --records %s: no records database there\n", printable(path->string()).c_str());
            return kExitBadInput;
        }
        if (args.json) std::printf("%s\n", listing_json(*path, {}, {}).dump(2, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
        else std::printf("No exams stored yet (%s).\n", printable(path->string()).c_str());
        if (!args.plot.empty()) std::fprintf(stderr, "echosim records: --plot: no sessions to plot\n");
        return args.plot.empty() ? kExitOk : kExitFailure;
    }
    const exam::Records records(*path, {.create = false});
    const auto sessions = records.sessions(args.trainee);
    std::vector<std::string> trainees;
    for (const exam::SessionRecord& s : sessions)
        if (std::find(trainees.begin(), trainees.end(), s.trainee) == trainees.end()) trainees.push_back(s.trainee);
    std::vector<exam::LearningCurve> curves;
    for (const std::string& t : trainees) curves.push_back(exam::learning_curve(records, t));

    if (args.json) {
        std::printf("%s\n", listing_json(*path, sessions, curves).dump(2, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
    } else {
        std::printf("Records: %s\n", printable(path->string()).c_str());
        if (sessions.empty()) {
            std::printf(args.trainee ? "No sessions of trainee '%s'.\n" : "No exams stored yet.\n",
                        args.trainee ? printable(*args.trainee).c_str() : "");
        } else {
            std::printf("%s", session_table(sessions).c_str());
            for (const exam::LearningCurve& c : curves) std::printf("\n%s", printable_lines(exam::learning_curve_table(c)).c_str());
        }
    }
    if (!args.plot.empty()) {
        if (curves.empty()) {
            std::fprintf(stderr, "echosim records: --plot %s: no sessions to plot\n", printable(args.plot.string()).c_str());
            return kExitFailure;
        }
        io::write_png(args.plot, exam::learning_curve_plot(curves));
        if (!args.json) std::printf("Learning curves: %s\n", printable(args.plot.string()).c_str());
    }
    return kExitOk;
}

int run_records_export(const RecordsArgs& args)
{
    const auto path = records_path("records export", args);
    if (!path) return kExitBadInput;
    if (!output_path_usable("records export", "--xapi", args.xapi)) return kExitBadInput;
    if (!outputs_distinct("records export", {{"--xapi", args.xapi}}, {{"--records", *path}})) return kExitBadInput;
    std::error_code ec;
    if (!std::filesystem::exists(*path, ec)) {
        std::fprintf(stderr, "echosim records export: %s: no records database there (no exam stored yet)\n", printable(path->string()).c_str());
        return args.records.empty() ? kExitFailure : kExitBadInput;
    }
    const exam::Records records(*path, {.create = false});
    exam::XapiOptions options;
    options.homepage = args.homepage;
    const std::string text = exam::xapi_statements(records, args.trainee, options);
    io::write_file<std::runtime_error>(args.xapi, text);
    const auto statements = nlohmann::json::parse(text).size();
    std::printf("Wrote %zu xAPI statements of %zu sessions to %s\n", statements, records.sessions(args.trainee).size(),
                printable(args.xapi.string()).c_str());
    return kExitOk;
}

int run_records_add(const RecordsArgs& args)
{
    const auto path = records_path("records add", args);
    if (!path) return kExitBadInput;
    exam::ExamReport report;
    try {
        report = exam::read_report_json(args.report);
    } catch (const exam::ReportError& e) {
        std::fprintf(stderr, "echosim records add: %s\n", printable(e.what()).c_str());
        return kExitBadInput;
    }
    if (args.trainee) report.trainee = *args.trainee;
    exam::Records records(*path);
    const std::int64_t id = exam::store_exam(records, report);
    std::printf("Stored session %lld (%s, %s) in %s\n", static_cast<long long>(id), printable(report.trainee).c_str(),
                printable(report.case_id).c_str(), printable(path->string()).c_str());
    return kExitOk;
}

}  // namespace echosim::app

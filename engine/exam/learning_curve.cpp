#include "exam/learning_curve.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "io/plot.hpp"

namespace echosim::exam {

CusumLimits cusum_limits(const CusumParameters& p)
{
    if (!(p.p0 > 0 && p.p0 < p.p1 && p.p1 < 1)) throw std::invalid_argument("CUSUM: the failure rates need 0 < p0 < p1 < 1");
    if (!(p.alpha > 0 && p.alpha < 0.5 && p.beta > 0 && p.beta < 0.5))
        throw std::invalid_argument("CUSUM: alpha and beta need to lie in (0, 0.5)");
    const double P = std::log(p.p1 / p.p0);
    const double Q = std::log((1 - p.p0) / (1 - p.p1));
    return {Q / (P + Q), std::log((1 - p.alpha) / p.beta) / (P + Q), std::log((1 - p.beta) / p.alpha) / (P + Q)};
}

std::vector<double> cusum_path(const std::vector<bool>& successes, const CusumLimits& limits)
{
    std::vector<double> path;
    path.reserve(successes.size());
    double sum = 0;
    for (const bool success : successes) {
        sum += success ? -limits.s : 1 - limits.s;
        path.push_back(sum);
    }
    return path;
}

const char* cusum_verdict_name(CusumVerdict v)
{
    switch (v) {
    case CusumVerdict::acceptable: return "acceptable";
    case CusumVerdict::unacceptable: return "unacceptable";
    case CusumVerdict::undecided: return "undecided";
    }
    return "?";
}

CusumVerdict cusum_verdict(const std::vector<double>& path, const CusumLimits& limits)
{
    if (path.empty()) return CusumVerdict::undecided;
    if (path.back() <= -limits.h0) return CusumVerdict::acceptable;
    if (path.back() >= limits.h1) return CusumVerdict::unacceptable;
    return CusumVerdict::undecided;
}

LearningCurve learning_curve(const Records& records, const std::string& trainee, const CusumParameters& parameters)
{
    LearningCurve curve;
    curve.trainee = trainee;
    curve.parameters = parameters;
    curve.limits = cusum_limits(parameters);
    std::map<std::string, std::size_t> index;  // type -> its place in curve.stations
    for (const SessionRecord& s : records.sessions(trainee)) {
        curve.sessions.push_back({s.id, s.case_id, s.score, s.passed});
        for (const StationRecord& st : records.stations(s.id)) {
            const std::string type = station_type(st.name, st.segment);
            auto [it, fresh] = index.try_emplace(type, curve.stations.size());
            if (fresh) curve.stations.push_back({type, {}, {}, CusumVerdict::undecided});
            curve.stations[it->second].successes.push_back(st.success());
        }
    }
    for (StationTypeCurve& c : curve.stations) {
        c.cusum = cusum_path(c.successes, curve.limits);
        c.verdict = cusum_verdict(c.cusum, curve.limits);
    }
    return curve;
}

std::string learning_curve_table(const LearningCurve& c)
{
    char buf[256];
    std::string out = "Trainee " + valid_utf8(c.trainee) + ": " + std::to_string(c.sessions.size()) + " session" +
                      (c.sessions.size() == 1 ? "" : "s") + "\n";
    out += "     #  session  case                          score  passed\n";
    for (std::size_t i = 0; i < c.sessions.size(); ++i) {
        const SessionPoint& s = c.sessions[i];
        std::snprintf(buf, sizeof buf, "  %4zu  %7lld  %-28.28s  %5s  %s\n", i + 1, static_cast<long long>(s.session_id),
                      valid_utf8(s.case_id).c_str(), fixed(100 * s.score, 0).c_str(), s.passed ? "yes" : "no");
        out += buf;
    }
    std::snprintf(buf, sizeof buf,
                  "CUSUM per station type (Bolsin & Colson 2000: p0 %s, p1 %s, alpha %s, beta %s; s %s, h0 %s, h1 %s):\n",
                  fixed(c.parameters.p0, 2).c_str(), fixed(c.parameters.p1, 2).c_str(), fixed(c.parameters.alpha, 2).c_str(),
                  fixed(c.parameters.beta, 2).c_str(), fixed(c.limits.s, 3).c_str(), fixed(c.limits.h0, 2).c_str(),
                  fixed(c.limits.h1, 2).c_str());
    out += buf;
    out += "  type          attempts  failures   CUSUM  verdict\n";
    for (const StationTypeCurve& t : c.stations) {
        std::size_t failures = 0;
        for (const bool ok : t.successes) failures += ok ? 0 : 1;
        std::snprintf(buf, sizeof buf, "  %-12.12s  %8zu  %8zu  %6s  %s\n", valid_utf8(t.type).c_str(), t.successes.size(), failures,
                      fixed(t.cusum.empty() ? 0.0 : t.cusum.back(), 2).c_str(), cusum_verdict_name(t.verdict));
        out += buf;
    }
    return out;
}

io::RgbaImage learning_curve_plot(const std::vector<LearningCurve>& curves, double pass_mark)
{
    std::vector<io::Plot> plots;
    for (const LearningCurve& c : curves) {
        io::Plot score;
        score.title = "Score per session: " + c.trainee;
        score.x_label = "session";
        score.y_label = "score [%]";
        score.y_range = io::Range{0, 105};  // a score of 100 % off the frame's edge
        io::Series points{"score", std::nullopt, {}, io::SeriesStyle::line_and_markers};
        for (std::size_t i = 0; i < c.sessions.size(); ++i) points.points.push_back({double(i + 1), 100 * c.sessions[i].score});
        const double n = std::max<double>(2, double(c.sessions.size()));
        score.x_range = io::Range{0.5, n + 0.5};
        score.series.push_back(std::move(points));
        score.series.push_back({"pass mark", io::Rgba{198, 40, 40, 255}, {{0.5, 100 * pass_mark}, {n + 0.5, 100 * pass_mark}}, io::SeriesStyle::line});
        plots.push_back(std::move(score));

        io::Plot cusum;
        cusum.title = "CUSUM per station type: " + c.trainee;
        cusum.x_label = "attempt";
        cusum.y_label = "CUSUM (failure +" + fixed(1 - c.limits.s, 2) + ", success -" + fixed(c.limits.s, 2) + ")";
        double most = 2;
        double lo = -c.limits.h0 - 0.5, hi = c.limits.h1 + 0.5;
        for (const StationTypeCurve& t : c.stations) {
            io::Series line{t.type, std::nullopt, {{0, 0}}, io::SeriesStyle::line};
            for (std::size_t i = 0; i < t.cusum.size(); ++i) {
                line.points.push_back({double(i + 1), t.cusum[i]});
                lo = std::min(lo, t.cusum[i] - 0.5);
                hi = std::max(hi, t.cusum[i] + 0.5);
            }
            most = std::max(most, double(t.cusum.size()));
            cusum.series.push_back(std::move(line));
        }
        cusum.series.push_back({"-h0 acceptable", io::Rgba{46, 125, 50, 255}, {{0, -c.limits.h0}, {most, -c.limits.h0}}, io::SeriesStyle::line});
        cusum.series.push_back({"+h1 unacceptable", io::Rgba{198, 40, 40, 255}, {{0, c.limits.h1}, {most, c.limits.h1}}, io::SeriesStyle::line});
        cusum.x_range = io::Range{0, most};
        cusum.y_range = io::Range{lo, hi};
        plots.push_back(std::move(cusum));
    }
    if (plots.empty()) throw std::invalid_argument("no trainee to plot");
    return io::render_plot_grid(plots, 2, 1800, std::uint32_t(600 * curves.size()));
}

}  // namespace echosim::exam

#include "fit/report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "io/partial_file.hpp"
#include "io/plot.hpp"
#include "tissue/nonlinear_spring.hpp"

namespace echosim::fit {
namespace {

nlohmann::json to_json(const ErrorStats& e)
{
    return {{"samples", e.samples}, {"mae_N", e.mae_N}, {"sd_N", e.sd_N}, {"rel_error", e.rel_error},
            {"mean_force_N", e.mean_force_N}, {"max_N", e.max_N}};
}

std::string line(const char* name, const ErrorStats& e)
{
    char buf[200];
    std::snprintf(buf, sizeof buf, "  %-9s %5d samples  MAE %.3f N  SD %.3f N  relative %.2f %%  max %.2f N\n", name,
                  e.samples, e.mae_N, e.sd_N, 100.0 * e.rel_error, e.max_N);
    return buf;
}

io::Plot curves(const MeasurementSet& set, const FitResult& r, ProbeKind probe)
{
    // one panel per point would be small; one plot with all 11 points, measured as markers and
    // the model as lines of the same colour, reads like the paper's figure
    io::Plot plot;
    plot.title = std::string(probe == ProbeKind::indenter ? "Indenter" : "Pseudo-probe") + ": measured (dots) vs model (lines)";
    plot.x_label = "penetration [mm]";
    plot.y_label = "force [N]";
    plot.legend = io::Corner::top_left;
    std::size_t colour = 0;
    for (int p : curve_points()) {
        io::Series measured, model;
        measured.style = io::SeriesStyle::markers;
        model.style = io::SeriesStyle::line;
        measured.colour = model.colour = io::palette_colour(colour++);
        model.name = "point " + std::to_string(p);
        for (std::size_t k = 0; k < set.samples.size(); ++k) {
            const Sample& s = set.samples[k];
            if (s.point != p || s.probe != probe) continue;
            measured.points.push_back({s.depth_mm, s.force_N});
            model.points.push_back({s.depth_mm, r.predicted[k]});
        }
        plot.series.push_back(std::move(model));
        plot.series.push_back(std::move(measured));
    }
    return plot;
}

}  // namespace

std::vector<int> curve_points() { return {0, 6, 9, 14, 20, 27, 35, 42, 49, 56, 63}; }

std::string summary_text(const FitResult& r)
{
    char head[300];
    std::snprintf(head, sizeof head,
                  "echosim fit (%s): step 1 %.3f s (%d iterations), step 2 %.3f s (%d iterations), total %.3f s\n"
                  "  lambda %.4f N/mm, mu %.3g N s/mm\n",
                  to_string(r.method), r.step1_seconds, r.step1_iterations, r.step2_seconds, r.step2_iterations, r.seconds(),
                  r.params.lambda, r.params.mu);
    return head + line("all", r.all) + line("indenter", r.indenter) + line("probe", r.probe);
}

void write_report(const std::filesystem::path& folder, const MeasurementSet& set, const FitResult& r)
{
    std::filesystem::create_directories(folder);
    nlohmann::json j = {{"method", to_string(r.method)},
                        {"seconds", r.seconds()},
                        {"step1", {{"seconds", r.step1_seconds}, {"iterations", r.step1_iterations}, {"cost", r.step1_cost}}},
                        {"step2", {{"seconds", r.step2_seconds}, {"iterations", r.step2_iterations}, {"cost", r.step2_cost}}},
                        {"all", to_json(r.all)},
                        {"indenter", to_json(r.indenter)},
                        {"probe", to_json(r.probe)},
                        {"lambda_N_per_mm", r.params.lambda},
                        {"mu_Ns_per_mm", r.params.mu},
                        {"a_per_N", r.params.a},
                        {"b_mm_per_N", r.params.b}};
    io::write_file<std::runtime_error>(folder / kReportFiles[0], j.dump(2) + "\n");

    // Fig. 4: how many samples the model misses by how much (signed: model - measured)
    std::vector<double> errors;
    for (std::size_t k = 0; k < set.samples.size(); ++k) errors.push_back(r.predicted[k] - set.samples[k].force_N);
    io::Plot hist;
    hist.title = "Error distribution, both probes";
    hist.x_label = "model - measured [N]";
    hist.y_label = "samples";
    hist.histograms.push_back(io::make_histogram_by_width(errors, 0.25));
    char note[160];
    std::snprintf(note, sizeof note, "MAE %.2f N, SD %.2f N\nrelative %.1f %%\n%d samples", r.all.mae_N, r.all.sd_N,
                  100.0 * r.all.rel_error, r.all.samples);
    hist.annotation = note;
    hist.legend = io::Corner::none;
    io::write_png(folder / kReportFiles[1], io::render_plot(hist, 900, 600));

    // Fig. 2: measured against fitted curves at 11 points, one figure per probe
    io::write_png(folder / kReportFiles[2], io::render_plot(curves(set, r, ProbeKind::indenter), 1000, 700));
    io::write_png(folder / kReportFiles[3], io::render_plot(curves(set, r, ProbeKind::probe), 1000, 700));
}

}  // namespace echosim::fit

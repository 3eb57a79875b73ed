#include <cstdio>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "fit/fit.hpp"
#include "fit/report.hpp"
#include "scene/leg.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::app {

int run_fit(const FitArgs& args)
{
    fit::MeasurementSet set;
    try {
        set = fit::read_measurements(args.data);
    } catch (const fit::MeasurementError& e) {
        std::fprintf(stderr, "echosim fit: %s\n", e.what());
        return kExitBadInput;
    }
    if (!output_path_usable("fit", "--out", args.out)) return kExitBadInput;
    std::vector<NamedPath> outputs{{"--out", args.out}};
    if (!args.report.empty())
        for (const char* file : fit::kReportFiles) outputs.push_back({"--report's " + std::string(file), args.report / file});
    if (!outputs_distinct("fit", outputs, {{"--data", args.data}})) return kExitBadInput;

    fit::FitOptions options;
    options.method = args.method == "steepest" ? fit::Method::steepest_descent : fit::Method::levenberg_marquardt;
    if (options.method == fit::Method::steepest_descent) options.max_iterations = 5000;
    fit::FitResult result;
    try {
        result = fit::fit_tissue(set, options);
    } catch (const fit::MeasurementError& e) {
        std::fprintf(stderr, "echosim fit: %s: %s\n", args.data.c_str(), e.what());
        return kExitBadInput;
    }

    // the simulator's model: our leg's patch geometry with the fitted parameters
    const scene::LegModel leg;
    tissue::TissueModel model = tissue::build_tissue_model(leg, result.params, 1);
    model.fit = fit::to_fit_statistics(result);
    model.provenance = "fitted by `echosim fit` (" + std::string(fit::to_string(result.method)) + ") to " +
                       args.data.filename().string();
    tissue::write_tissue_model(args.out, model);
    if (!args.report.empty()) fit::write_report(args.report, set, result);

    if (args.json) {
        const nlohmann::json j = {{"mae_N", result.all.mae_N},
                                  {"sd_N", result.all.sd_N},
                                  {"rel_error", result.all.rel_error},
                                  {"seconds", result.seconds()},
                                  {"step1_seconds", result.step1_seconds},
                                  {"step2_seconds", result.step2_seconds},
                                  {"samples", result.all.samples},
                                  {"method", fit::to_string(result.method)},
                                  {"indenter", {{"mae_N", result.indenter.mae_N}, {"sd_N", result.indenter.sd_N}, {"rel_error", result.indenter.rel_error}}},
                                  {"probe", {{"mae_N", result.probe.mae_N}, {"sd_N", result.probe.sd_N}, {"rel_error", result.probe.rel_error}}},
                                  {"lambda_N_per_mm", result.params.lambda},
                                  {"model", args.out.string()}};
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    std::printf("%s", fit::summary_text(result).c_str());
    std::printf("echosim fit: wrote %s%s%s\n", args.out.c_str(), args.report.empty() ? "" : " and the report in ",
                args.report.c_str());
    return kExitOk;
}

}  // namespace echosim::app

// Suite "fit": the full two-step fit of the tissue model on the shipped measurement set
// (assets/measurements/thigh.csv), with Levenberg-Marquardt and with the paper's steepest descent.
// Counters carry the fit's quality, so the table shows speed and error side by side.
#include <benchmark/benchmark.h>

#include "bench/suites.hpp"
#include "core/assets.hpp"
#include "fit/fit.hpp"

namespace echosim::bench {
namespace {

void fit_once(benchmark::State& state, const fit::MeasurementSet& set, fit::Method method)
{
    fit::FitOptions options;
    options.method = method;
    if (method == fit::Method::steepest_descent) options.max_iterations = 5000;
    fit::FitResult r;
    for (auto _ : state) r = fit::fit_tissue(set, options);
    state.counters["mae_N"] = r.all.mae_N;
    state.counters["sd_N"] = r.all.sd_N;
    state.counters["rel_error"] = r.all.rel_error;
    state.counters["step1_s"] = r.step1_seconds;
    state.counters["step2_s"] = r.step2_seconds;
    state.counters["iterations"] = r.step1_iterations + r.step2_iterations;
    state.counters["samples"] = r.all.samples;
}

}  // namespace

std::shared_ptr<void> register_fit(const SuiteOptions& options)
{
    auto set = std::make_shared<fit::MeasurementSet>(fit::read_measurements(asset_path("measurements/thigh.csv")));
    for (fit::Method m : {fit::Method::levenberg_marquardt, fit::Method::steepest_descent})
        benchmark::RegisterBenchmark((std::string("fit/") + fit::to_string(m)).c_str(),
                                     [set = set.get(), m](benchmark::State& s) { fit_once(s, *set, m); })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(options.min_time_s);
    return set;
}

}  // namespace echosim::bench

// Parameter estimation of the two-layer model (paper §3.2.1), as two non-linear least-squares
// problems solved with Ceres (automatic differentiation, robust Huber loss against points spoiled
// by leg motion):
//   step 1: the indenter data of each point, fitted by its non-linear spring alone (a, b);
//   step 2: seeded by step 1, all 64 (a, b) and the surface stiffness lambda together, on both
//           probes, through the simplified interaction model (interaction.hpp).
// Parameters are optimised as logarithms, which keeps them positive for every method, including the
// paper's steepest descent (kept as an option for comparison: Ceres' line-search minimiser in the
// steepest-descent direction). The default is Levenberg-Marquardt.
#pragma once

#include <string>
#include <vector>

#include "fit/interaction.hpp"
#include "fit/measurements.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::fit {

enum class Method { levenberg_marquardt, steepest_descent };
const char* to_string(Method m);

struct FitOptions {
    Method method = Method::levenberg_marquardt;
    double huber_N = 1.0;       // residuals beyond this [N] count linearly, not quadratically
    int max_iterations = 200;   // per step (steepest descent needs far more; see the report)
    double damping_ratio = 1.0; // mu is not identifiable from quasi-static data: set for this ratio
};

struct ErrorStats {
    int samples = 0;
    double mae_N = 0;       // mean absolute error
    double sd_N = 0;        // standard deviation of the absolute error (as the paper reports it)
    double mean_force_N = 0;
    double rel_error = 0;   // mae / mean measured force (a fraction)
    double max_N = 0;
};

struct FitResult {
    tissue::SampleParameters params;
    std::vector<double> predicted;  // model force for each sample of the set [N]
    ErrorStats all, indenter, probe;
    double step1_seconds = 0, step2_seconds = 0;
    int step1_iterations = 0, step2_iterations = 0;
    double step1_cost = 0, step2_cost = 0;  // final robust cost (what the optimiser minimised)
    Method method = Method::levenberg_marquardt;

    double seconds() const { return step1_seconds + step2_seconds; }
};

FitResult fit_tissue(const MeasurementSet& set, const FitOptions& options = {});

// The error statistics of `predicted` against the set's forces, over the samples of `which` probe
// (all samples when `which` is null).
ErrorStats error_stats(const MeasurementSet& set, const std::vector<double>& predicted, const ProbeKind* which = nullptr);

// The model force of every sample with the given parameters (infeasible ones: +infinity).
std::vector<double> predict(const MeasurementSet& set, const tissue::SampleParameters& params);

// Fills the model's fit statistics from a result.
tissue::FitStatistics to_fit_statistics(const FitResult& r);

}  // namespace echosim::fit

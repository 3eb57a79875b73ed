#include "fit/fit.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

#include <ceres/ceres.h>
#include <glm/geometric.hpp>
#include <glog/logging.h>

#include "tissue/nonlinear_spring.hpp"
#include "tissue/physical_ranges.hpp"

namespace echosim::fit {
namespace {

using tissue::SampleGrid;
using Clock = std::chrono::steady_clock;

// step 1: one indenter sample against its point's spring, parameters (log a, log b)
struct SpringResidual {
    double depth, force;
    template <class T>
    bool operator()(const T* log_ab, T* residual) const
    {
        const T a = exp(log_ab[0]), b = exp(log_ab[1]);
        if (!tissue::spring_holds(T(depth), a, b)) return false;
        residual[0] = tissue::spring_force(T(depth), a, b) - force;
        return true;
    }
};

// step 2: one sample through the interaction model; parameter blocks: (log a, log b) of each
// contact node, then log lambda
struct InteractionResidual {
    const InteractionSample* sample;
    template <class T>
    bool operator()(T const* const* blocks, T* residual) const
    {
        const std::size_t n = sample->contacts.size();
        auto ab = [&](int node, int which) {
            for (std::size_t k = 0; k < n; ++k)
                if (sample->contacts[k].node == node) return exp(blocks[k][which]);
            return T(0);  // not reached: every contact node has its block
        };
        T force;
        if (!interaction_force(*sample, ab, T(exp(blocks[n][0])), force)) return false;
        residual[0] = force - sample->force;
        return true;
    }
};

// Solves one step's problem with the chosen method; Ceres' failures become exceptions naming the step.
void solve(ceres::Problem& problem, const FitOptions& options, const char* step, int& iterations, double& cost)
{
    ceres::Solver::Options o;
    o.max_num_iterations = options.max_iterations;
    o.num_threads = 1;
    o.logging_type = ceres::SILENT;
    o.function_tolerance = 1e-10;
    o.gradient_tolerance = 1e-12;
    o.parameter_tolerance = 1e-10;
    if (options.method == Method::steepest_descent) {
        o.minimizer_type = ceres::LINE_SEARCH;
        o.line_search_direction_type = ceres::STEEPEST_DESCENT;
        o.line_search_type = ceres::ARMIJO;
    } else {
        o.minimizer_type = ceres::TRUST_REGION;
        o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        o.linear_solver_type = ceres::DENSE_QR;
    }
    ceres::Solver::Summary summary;
    ceres::Solve(o, &problem, &summary);
    if (summary.termination_type == ceres::FAILURE) throw std::runtime_error(std::string("tissue fit, ") + step + ": " + summary.message);
    iterations = int(summary.iterations.size());
    cost = summary.final_cost;
}

// The model force of every prepared sample (infeasible ones: +infinity), in the set's order.
std::vector<double> predict(const std::vector<InteractionSample>& prepared, std::size_t samples, const tissue::SampleParameters& params)
{
    std::vector<double> out(samples);
    auto ab = [&](int node, int which) { return which == 0 ? params.a[std::size_t(node)] : params.b[std::size_t(node)]; };
    for (const auto& s : prepared) {
        double f = 0;
        out[s.sample] = interaction_force(s, ab, params.lambda, f) ? f : std::numeric_limits<double>::infinity();
    }
    return out;
}

// A feasible start for one point's spring from its indenter samples: u = b F - a u F is linear in
// (a, b), so ordinary least squares gives a first guess, then kept inside the bottoming limit.
void initial_spring(const std::vector<std::pair<double, double>>& uf, double& a, double& b)
{
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0, umax = 0;
    for (auto [u, f] : uf) {
        const double x1 = f, x2 = -u * f;  // u = b x1 + a x2
        s11 += x1 * x1, s12 += x1 * x2, s22 += x2 * x2, r1 += x1 * u, r2 += x2 * u;
        umax = std::max(umax, u);
    }
    const double det = s11 * s22 - s12 * s12;
    b = det != 0 ? (r1 * s22 - r2 * s12) / det : 1.0;
    a = det != 0 ? (s11 * r2 - s12 * r1) / det : 0.0;
    if (!(b > 1e-3)) b = uf.empty() ? 1.0 : std::max(1e-3, uf.back().first / std::max(uf.back().second, 1e-3));
    a = std::clamp(a, 1e-4 * b, 0.95 * b / std::max(umax, 1e-3));
}

// Measurements that cannot determine the model are refused before the optimiser runs: the sample
// points must be distinct places on the skin, and each point's indenter samples must reach at
// least two depths with a force (a spring's a and b are two unknowns).
void check_identifiable(const MeasurementSet& set, const SampleMesh& mesh)
{
    for (const auto& spring : mesh.springs)
        if (!tissue::range_defect(tissue::kSpringRestLength, spring.rest_length).empty()) {
            char why[200];
            std::snprintf(why, sizeof why, "measurements: sample points %u and %u lie %g mm apart: the points must be distinct places on "
                          "the skin, %g to %g mm from their neighbours", spring.i, spring.j, spring.rest_length,
                          tissue::kSpringRestLength.lo, tissue::kSpringRestLength.hi);
            throw MeasurementError(why);
        }
    std::array<std::vector<double>, SampleGrid::count> depths;
    for (const Sample& s : set.samples)
        if (s.probe == ProbeKind::indenter && s.force_N > 0) depths[std::size_t(s.point)].push_back(s.depth_mm);
    for (int p = 0; p < SampleGrid::count; ++p) {
        auto& d = depths[std::size_t(p)];
        std::sort(d.begin(), d.end());
        const auto distinct = std::unique(d.begin(), d.end()) - d.begin();
        if (distinct < 2)
            throw MeasurementError("measurements: point " + std::to_string(p) + " has indenter samples with a force at " +
                                   std::to_string(distinct) + " depth(s): its spring's two parameters need at least two");
    }
}

}  // namespace

const char* to_string(Method m) { return m == Method::steepest_descent ? "steepest-descent" : "levenberg-marquardt"; }

ErrorStats error_stats(const MeasurementSet& set, const std::vector<double>& predicted, const ProbeKind* which)
{
    ErrorStats e;
    double sum = 0, sum2 = 0, force = 0;
    for (std::size_t k = 0; k < set.samples.size(); ++k) {
        if (which && set.samples[k].probe != *which) continue;
        const double err = std::abs(predicted[k] - set.samples[k].force_N);
        sum += err, sum2 += err * err, force += set.samples[k].force_N;
        e.max_N = std::max(e.max_N, err);
        ++e.samples;
    }
    if (e.samples == 0) return e;
    e.mae_N = sum / e.samples;
    e.sd_N = std::sqrt(std::max(0.0, sum2 / e.samples - e.mae_N * e.mae_N));
    e.mean_force_N = force / e.samples;
    e.rel_error = e.mean_force_N > 0 ? e.mae_N / e.mean_force_N : 0;
    return e;
}

std::vector<double> predict(const MeasurementSet& set, const tissue::SampleParameters& params)
{
    return predict(prepare_interaction(sample_mesh(set), set), set.samples.size(), params);
}

FitResult fit_tissue(const MeasurementSet& set, const FitOptions& options)
{
    // Ceres reports through glog; its failures reach the caller as exceptions instead
    static std::once_flag quiet;
    std::call_once(quiet, [] {
        if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("echosim");
        FLAGS_minloglevel = google::GLOG_FATAL;
    });
    FitResult result;
    result.method = options.method;
    const SampleMesh mesh = sample_mesh(set);
    check_identifiable(set, mesh);
    const std::vector<InteractionSample> prepared = prepare_interaction(mesh, set);

    // step 1: every point's spring from its indenter samples alone
    const auto t0 = Clock::now();
    std::array<std::array<double, 2>, SampleGrid::count> log_ab{};
    {
        std::array<std::vector<std::pair<double, double>>, SampleGrid::count> uf;
        for (const Sample& s : set.samples)
            if (s.probe == ProbeKind::indenter) uf[std::size_t(s.point)].push_back({s.depth_mm, s.force_N});
        ceres::Problem problem;
        for (int p = 0; p < SampleGrid::count; ++p) {
            double a = 0, b = 0;
            initial_spring(uf[std::size_t(p)], a, b);
            log_ab[std::size_t(p)] = {std::log(a), std::log(b)};
            for (auto [u, f] : uf[std::size_t(p)])
                problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SpringResidual, 1, 2>(new SpringResidual{u, f}),
                                         new ceres::HuberLoss(options.huber_N), log_ab[std::size_t(p)].data());
        }
        solve(problem, options, "step 1", result.step1_iterations, result.step1_cost);
    }
    const auto t1 = Clock::now();

    // step 2: all springs and lambda together on both probes, from step 1 and a modest lambda.
    // The probe pushes nodes deeper than the indenter did; a start where a step-1 spring would
    // bottom out before the deepest probe sample is infeasible, so such springs start softer.
    double log_lambda = std::log(0.05);
    {
        std::array<double, SampleGrid::count> deepest{};
        for (const InteractionSample& s : prepared)
            for (const ContactTerm& c : s.contacts) deepest[std::size_t(c.node)] = std::max(deepest[std::size_t(c.node)], c.compression);
        for (int p = 0; p < SampleGrid::count; ++p) {
            const double b = std::exp(log_ab[std::size_t(p)][1]);
            const double a_max = 0.8 * b / std::max(deepest[std::size_t(p)], 1e-3);
            log_ab[std::size_t(p)][0] = std::min(log_ab[std::size_t(p)][0], std::log(a_max));
        }
    }
    {
        ceres::Problem problem;
        for (const InteractionSample& s : prepared) {
            auto* cost = new ceres::DynamicAutoDiffCostFunction<InteractionResidual, 4>(new InteractionResidual{&s});
            std::vector<double*> blocks;
            for (const ContactTerm& c : s.contacts) {
                cost->AddParameterBlock(2);
                blocks.push_back(log_ab[std::size_t(c.node)].data());
            }
            cost->AddParameterBlock(1);
            blocks.push_back(&log_lambda);
            cost->SetNumResiduals(1);
            problem.AddResidualBlock(cost, new ceres::HuberLoss(options.huber_N), blocks);
        }
        solve(problem, options, "step 2", result.step2_iterations, result.step2_cost);
    }
    const auto t2 = Clock::now();
    result.step1_seconds = std::chrono::duration<double>(t1 - t0).count();
    result.step2_seconds = std::chrono::duration<double>(t2 - t1).count();

    for (int p = 0; p < SampleGrid::count; ++p) {
        result.params.a[std::size_t(p)] = std::exp(log_ab[std::size_t(p)][0]);
        result.params.b[std::size_t(p)] = std::exp(log_ab[std::size_t(p)][1]);
    }
    result.params.lambda = std::exp(log_lambda);
    // mu for the wanted damping ratio of one node's mass on its rest stiffness (units: N/mm is
    // 1000 kg/s^2, so sqrt(k m) in kg/s is N s/m, and 1e-3 of that is N s/mm)
    // a node's share of the skin: the grid's cells' area over its nodes
    double area = 0;
    for (int r = 0; r + 1 < SampleGrid::rows; ++r)
        for (int c = 0; c + 1 < SampleGrid::cols; ++c) {
            const glm::dvec3& p = mesh.position[std::size_t(SampleGrid::index(r, c))];
            area += glm::length(glm::cross(mesh.position[std::size_t(SampleGrid::index(r + 1, c))] - p,
                                           mesh.position[std::size_t(SampleGrid::index(r, c + 1))] - p));
        }
    const double mean_area = area / SampleGrid::count;
    double mean_k = 0;
    for (double b : result.params.b) mean_k += 1.0 / b;
    mean_k /= SampleGrid::count;
    const double node_mass = mean_area * tissue::kSurfaceMassPerArea;
    result.params.mu = 2.0 * options.damping_ratio * std::sqrt(1000.0 * (mean_k + 8.0 * result.params.lambda) * node_mass) * 1e-3;

    // data that cannot pin a parameter down lets the optimiser walk it anywhere (1e-128 N/mm):
    // refused, not returned as a model
    if (const tissue::ParameterDefect d = tissue::sample_parameters_defect(result.params))
        throw MeasurementError("measurements: the fit's " + d.field + " came out at " + d.why +
                               ": these measurements do not determine the model");

    result.predicted = predict(prepared, set.samples.size(), result.params);
    const ProbeKind indenter = ProbeKind::indenter, probe = ProbeKind::probe;
    result.all = error_stats(set, result.predicted);
    result.indenter = error_stats(set, result.predicted, &indenter);
    result.probe = error_stats(set, result.predicted, &probe);
    return result;
}

tissue::FitStatistics to_fit_statistics(const FitResult& r)
{
    tissue::FitStatistics s;
    s.mae_N = r.all.mae_N;
    s.sd_N = r.all.sd_N;
    s.rel_error = r.all.rel_error;
    s.mae_indenter_N = r.indenter.mae_N;
    s.mae_probe_N = r.probe.mae_N;
    s.samples = r.all.samples;
    s.method = to_string(r.method);
    s.seconds = r.seconds();
    return s;
}

}  // namespace echosim::fit

#include "fit/fit.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "fit/reference_tissue.hpp"
#include "scene/leg.hpp"

namespace echosim::fit {
namespace {

using tissue::SampleGrid;

const MeasurementSet& campaign()
{
    static const MeasurementSet set = simulate_campaign(scene::LegModel{}, ReferenceTissue{}, CampaignOptions{});
    return set;
}

TEST(Campaign, FollowsThePapersProtocol)
{
    const MeasurementSet& set = campaign();
    EXPECT_EQ(set.point_count(), 64);
    EXPECT_GT(set.samples.size(), 1000u);
    int counts[64][2] = {};
    double max_force = 0;
    for (const Sample& s : set.samples) {
        ++counts[s.point][s.probe == ProbeKind::probe];
        max_force = std::max(max_force, s.force_N);
        EXPECT_NEAR(std::fmod(s.depth_mm, 2.0), 0.0, 1e-9);  // 2 mm steps
    }
    for (auto& c : counts)
        for (int n : c) {
            EXPECT_GE(n, 6);
            EXPECT_LE(n, 18);
        }
    EXPECT_GT(max_force, 20.0);  // tens of newtons at the deepest
}

TEST(Campaign, PseudoProbeIsStifferThanIndenter)
{
    const ReferenceTissue tissue;
    const scene::LegModel leg;
    for (double depth : {4.0, 10.0, 16.0})
        EXPECT_GT(tissue.probe_force(leg, depth, 0.5, 0.5), 2.0 * tissue.indenter_force(depth, 0.5, 0.5));
}

// Data made by the two-layer model itself, without noise: the fit must find its parameters.
TEST(Fit, RecoversKnownParametersFromTheModelsOwnData)
{
    MeasurementSet set = campaign();
    tissue::SampleParameters truth;
    for (int p = 0; p < SampleGrid::count; ++p) {
        const int r = SampleGrid::row_of(p), c = SampleGrid::col_of(p);
        truth.b[std::size_t(p)] = 0.55 + 0.05 * r + 0.03 * c;                        // 1.8 .. 1.1 N/mm at rest
        truth.a[std::size_t(p)] = truth.b[std::size_t(p)] / (40.0 + 2.0 * c - r);    // bottoms out at 33 .. 54 mm
    }
    truth.lambda = 0.12;
    const std::vector<double> forces = predict(set, truth);
    for (std::size_t k = 0; k < set.samples.size(); ++k) {
        ASSERT_TRUE(std::isfinite(forces[k]));
        set.samples[k].force_N = forces[k];
    }
    const FitResult r = fit_tissue(set);
    EXPECT_NEAR(r.params.lambda, truth.lambda, 0.01 * truth.lambda);
    for (int p = 0; p < SampleGrid::count; ++p) {
        EXPECT_NEAR(r.params.b[std::size_t(p)], truth.b[std::size_t(p)], 0.01 * truth.b[std::size_t(p)]) << "point " << p;
        EXPECT_NEAR(r.params.a[std::size_t(p)], truth.a[std::size_t(p)], 0.03 * truth.a[std::size_t(p)]) << "point " << p;
    }
    EXPECT_LT(r.all.mae_N, 1e-3);
}

TEST(Fit, ShippedMeasurementsAreFittedWithinFivePercent)
{
    const auto path = std::filesystem::path(ECHOSIM_ASSET_DIR) / "measurements" / "thigh.csv";
    const MeasurementSet set = read_measurements(path);
    const FitResult r = fit_tissue(set);
    EXPECT_LE(r.all.rel_error, 0.05) << "MAE " << r.all.mae_N << " N of mean force " << r.all.mean_force_N << " N";
    EXPECT_GT(r.params.lambda, 0.0);
    // neither probe is sacrificed to the other: each within 10 % (measured on this set: indenter
    // 9.0 %, its smaller forces weigh more in a relative error; probe 3.1 %)
    EXPECT_LE(r.indenter.rel_error, 0.10);
    EXPECT_LE(r.probe.rel_error, 0.10);
}

TEST(Fit, SteepestDescentEndsNoBetterThanLevenbergMarquardt)
{
    FitOptions sd;
    sd.method = Method::steepest_descent;
    sd.max_iterations = 300;
    const FitResult lm = fit_tissue(campaign());
    const FitResult slow = fit_tissue(campaign(), sd);
    EXPECT_TRUE(std::isfinite(slow.all.mae_N));
    EXPECT_GE(slow.step2_cost, lm.step2_cost * 0.999);
}

std::string fit_error(const MeasurementSet& set)
{
    try {
        fit_tissue(set);
    } catch (const MeasurementError& e) {
        return e.what();
    }
    return "no error";
}

// Measurements that cannot determine the model: refused before the fit, naming why, instead of a
// model with lambda = 1e-128 N/mm.
TEST(Fit, DegenerateMeasurementsAreRefused)
{
    MeasurementSet one_place = campaign();
    for (Sample& s : one_place.samples) s.position = campaign().samples.front().position;
    std::string why = fit_error(one_place);
    EXPECT_NE(why.find("sample points 0 and 1 lie 0 mm apart"), std::string::npos) << why;

    MeasurementSet one_depth = campaign();
    for (Sample& s : one_depth.samples)
        if (s.point == 17) s.depth_mm = 4.0;
    why = fit_error(one_depth);
    EXPECT_NE(why.find("point 17 has indenter samples with a force at 1 depth(s)"), std::string::npos) << why;

    // forces that do not grow with depth: no spring explains them, and lambda runs off
    MeasurementSet flat = campaign();
    for (Sample& s : flat.samples) s.force_N = 0.001 * (1 + s.point % 2);
    why = fit_error(flat);
    EXPECT_NE(why.find("do not determine the model"), std::string::npos) << why;
}

}  // namespace
}  // namespace echosim::fit

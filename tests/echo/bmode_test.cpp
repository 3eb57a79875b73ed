#include "echo/bmode.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "echo/bmode_gates.hpp"

namespace echosim::echo {
namespace {

const scene::LegModel& leg()
{
    static const scene::LegModel model;
    return model;
}

struct Homogeneous : Medium {
    Tissue tissue_at(const glm::dvec3&) const override { return Tissue::muscle; }
};

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }
double stddev(const std::vector<double>& v)
{
    const double m = mean(v);
    double s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / double(v.size()));
}

TEST(BMode, SpeckleIsFullyDevelopedInHomogeneousTissue)
{
    // Rayleigh statistics of the envelope: mean / standard deviation = sqrt(pi / (4 - pi)) = 1.913
    ScanSpec spec;
    spec.texture = false;
    spec.tgc_db_per_cm_mhz = 0.9;  // exactly the muscle's attenuation: no depth trend
    const BModeImage img = synthesize(Homogeneous{}, leg().probe_rest_pose(0.5f, 0.5f), spec);
    std::vector<double> env;
    // away from the image's edges, where the PSF is cut
    for (std::uint32_t j = 50; j < img.height - 50; ++j)
        for (std::uint32_t i = 50; i < img.width - 50; ++i) env.push_back(img.envelope[j * img.width + i]);
    EXPECT_NEAR(mean(env) / stddev(env), 1.913, 0.06);
}

TEST(BMode, SpeckleIsFixedInTheBody)
{
    // the same scatterers seen from a probe moved 0.05 mm: nearly the same image; moved 4 mm
    // along the thigh (beyond the beam's thickness): unrelated speckle
    const Homogeneous medium;
    ScanSpec spec;
    spec.texture = false;
    spec.depth_mm = 20;
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    auto moved = [&](double mm) {
        Pose p = pose;
        p.position += float(mm) * pose.axis_z();
        return synthesize(medium, p, spec).envelope;
    };
    auto correlation = [](const std::vector<float>& a, const std::vector<float>& b) {
        const double ma = std::accumulate(a.begin(), a.end(), 0.0) / double(a.size());
        const double mb = std::accumulate(b.begin(), b.end(), 0.0) / double(b.size());
        double ab = 0, aa = 0, bb = 0;
        for (std::size_t k = 0; k < a.size(); ++k) {
            ab += (a[k] - ma) * (b[k] - mb);
            aa += (a[k] - ma) * (a[k] - ma);
            bb += (b[k] - mb) * (b[k] - mb);
        }
        return ab / std::sqrt(aa * bb);
    };
    const auto here = moved(0.0);
    EXPECT_GT(correlation(here, moved(0.05)), 0.8);
    EXPECT_LT(correlation(here, moved(4.0)), 0.35);
    EXPECT_EQ(here, moved(0.0));  // deterministic
}

// mean envelope over the pixels of one tissue at least 1 mm (10 pixels) inside it, away from the
// bright echoes of its boundaries that the point-spread function spreads; -1 if there are none
double tissue_mean(const BModeImage& img, Tissue t)
{
    const int margin = 10, w = int(img.width), h = int(img.height);
    auto is = [&](int i, int j) { return i >= 0 && j >= 0 && i < w && j < h && img.labels[std::size_t(j * w + i)] == std::uint8_t(t); };
    double sum = 0;
    int n = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            if (is(i, j) && is(i - margin, j) && is(i + margin, j) && is(i, j - margin) && is(i, j + margin))
                sum += img.envelope[std::size_t(j * w + i)], ++n;
    return n ? sum / n : -1.0;
}

TEST(BMode, VesselsAreAnechoicAndThrombiAreNot)
{
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    const ScanSpec spec;
    const BModeImage healthy = synthesize(PhantomMedium(Phantom(leg(), Case::healthy)), pose, spec);
    const BModeImage acute = synthesize(PhantomMedium(Phantom(leg(), Case::dvt_acute)), pose, spec);
    const BModeImage chronic = synthesize(PhantomMedium(Phantom(leg(), Case::dvt_chronic)), pose, spec);
    const double muscle = tissue_mean(healthy, Tissue::muscle);
    ASSERT_GT(muscle, 0);
    EXPECT_LT(tissue_mean(healthy, Tissue::vein_lumen), 0.1 * muscle);  // anechoic blood
    EXPECT_LT(tissue_mean(healthy, Tissue::artery_lumen), 0.1 * muscle);
    EXPECT_LT(tissue_mean(healthy, Tissue::thrombus), 0.0);               // none in the healthy case
    const double acute_clot = tissue_mean(acute, Tissue::thrombus), chronic_clot = tissue_mean(chronic, Tissue::organised_thrombus);
    EXPECT_GT(acute_clot, 2.0 * tissue_mean(acute, Tissue::artery_lumen));  // hypo-echoic, not anechoic
    EXPECT_LT(acute_clot, 0.5 * muscle);
    EXPECT_GT(chronic_clot, 2.0 * acute_clot);                                // echogenic
}

TEST(BMode, BoneCastsAShadow)
{
    const Phantom phantom(leg(), Case::healthy);
    ScanSpec spec;
    spec.depth_mm = 60;
    const BModeImage img = synthesize(PhantomMedium(phantom), leg().probe_rest_pose(0.5f, 0.5f), spec);
    // in each column that meets the femur, the echo 2 to 6 mm below the cortex's top is far weaker
    // than 2 to 6 mm above it
    int columns = 0;
    for (std::uint32_t i = 0; i < img.width; ++i) {
        std::uint32_t top = 0;
        for (std::uint32_t j = 0; j < img.height && !top; ++j)
            if (img.labels[j * img.width + i] == std::uint8_t(Tissue::bone_cortex)) top = j;
        if (top < 80 || top + 80 > img.height) continue;
        // only where this beam and its neighbours 1 mm either side go into the bone (the lateral
        // point-spread function carries echoes sideways near the bone's edge)
        auto into_bone = [&](std::uint32_t c) {
            if (c >= img.width) return false;
            const auto deep = img.labels[(top + 60) * img.width + c];
            return deep == std::uint8_t(Tissue::bone_cortex) || deep == std::uint8_t(Tissue::bone_marrow);
        };
        if (i < 10 || !into_bone(i - 10) || !into_bone(i) || !into_bone(i + 10)) continue;
        double above = 0, below = 0;
        for (std::uint32_t j = top - 60; j < top - 20; ++j) above += img.envelope[j * img.width + i];
        for (std::uint32_t j = top + 20; j < top + 60; ++j) below += img.envelope[j * img.width + i];
        EXPECT_LT(below, 0.05 * above) << "column " << i;
        ++columns;
    }
    EXPECT_GT(columns, 20);
}

// Issue 33's speckle gates on the CPU twin (the GPU's: tests/image/bmode_gpu_test.cpp, same body):
// Rayleigh statistics, and speckle as large as the configured point-spread function.
TEST(BMode, TwinSpeckleGates)
{
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    const ScanSpec spec = gates::homogeneous_spec(30, 30);
    const io::Volume labels = gates::muscle_volume(pose, spec);
    const BModeImage img = synthesize(labels, pose, spec);
    // the twin with the tissue from the volume is the twin with the tissue asked directly
    EXPECT_EQ(img.pixels, synthesize(Homogeneous{}, pose, spec).pixels);
    gates::expect_speckle_gates(img, spec, "CPU twin");
}

TEST(BMode, LabelVolumeKeepsThePhantomsTissues)
{
    // the phantom voxelised over one frame (0.2 mm in plane) against the tissue asked at every pixel:
    // they differ only along boundaries, within a voxel
    const Phantom phantom(leg(), Case::dvt_acute);
    const PhantomMedium medium(phantom);
    const Pose pose = leg().probe_rest_pose(0.5f, 0.5f);
    ScanSpec spec;
    spec.depth_mm = 40;
    const io::Volume labels = voxelise_frames(medium, std::span(&pose, 1), spec);
    const BModeImage direct = synthesize(medium, pose, spec), voxelised = synthesize(labels, pose, spec);
    std::size_t same = 0;
    for (std::size_t k = 0; k < direct.labels.size(); ++k) same += direct.labels[k] == voxelised.labels[k];
    const double agree = double(same) / double(direct.labels.size());
    std::printf("labels from the 0.2 mm volume agree with the phantom's at %.2f %% of pixels\n", 100 * agree);
    EXPECT_GT(agree, 0.97);
    // every tissue the frame shows is in the volume's frame too, about as large
    for (int t = 0; t < kTissueCount; ++t) {
        const auto count = [&](const std::vector<std::uint8_t>& v) { return double(std::count(v.begin(), v.end(), std::uint8_t(t))); };
        const double a = count(direct.labels), b = count(voxelised.labels);
        if (a > 500) {
            EXPECT_NEAR(b / a, 1.0, 0.1) << tissue_name(Tissue(t));
        }
    }
}

}  // namespace
}  // namespace echosim::echo

// The B-mode model's quality gates (issue 33), one body for the CPU twin (tests/echo/bmode_test.cpp)
// and the GPU kernels (tests/image/bmode_gpu_test.cpp): speckle statistics measured on the envelope
// (before log compression) of an image of homogeneous tissue.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "echo/bmode.hpp"

namespace echosim::echo::gates {

// A scan of plain speckle: no texture, the TGC exactly the muscle's attenuation (no depth trend).
inline ScanSpec homogeneous_spec(double width_mm, double depth_mm)
{
    ScanSpec spec;
    spec.width_mm = width_mm;
    spec.depth_mm = depth_mm;
    spec.texture = false;
    spec.tgc_db_per_cm_mhz = 0.9;
    return spec;
}

// An all-muscle label volume around a pose's frame, on a grid of its own (1 mm).
inline io::Volume muscle_volume(const Pose& pose, const ScanSpec& spec)
{
    struct Muscle : Medium {
        Tissue tissue_at(const glm::dvec3&) const override { return Tissue::muscle; }
    };
    LabelVolumeOptions o;
    o.in_plane_mm = 1.0;
    return voxelise_frames(Muscle{}, std::span(&pose, 1), spec, o);
}

// The envelope inside the image, `margin` pixels from its edges (where the PSF is cut).
inline std::vector<double> interior(const BModeImage& img, std::uint32_t margin)
{
    std::vector<double> v;
    for (std::uint32_t j = margin; j + margin < img.height; ++j)
        for (std::uint32_t i = margin; i + margin < img.width; ++i) v.push_back(img.envelope[std::size_t(j) * img.width + i]);
    return v;
}

// mean / standard deviation of the envelope: sqrt(pi / (4 - pi)) = 1.913 for Rayleigh speckle
inline double speckle_snr(const BModeImage& img, std::uint32_t margin)
{
    const std::vector<double> v = interior(img, margin);
    double m = 0, s = 0;
    for (double x : v) m += x;
    m /= double(v.size());
    for (double x : v) s += (x - m) * (x - m);
    return m / std::sqrt(s / double(v.size()));
}

// Full width at half maximum [mm] of the intensity (envelope squared) autocovariance along the
// rows (`lateral`) or the columns: for a Gaussian amplitude PSF of FWHM w over white scatterers it
// is w itself (the field's autocorrelation is the PSF's, sqrt 2 wider; the intensity's is its square).
inline double autocovariance_fwhm_mm(const BModeImage& img, std::uint32_t margin, bool lateral, double pixel_mm)
{
    const int w = int(img.width), h = int(img.height), m = int(margin);
    double mean = 0;
    int n = 0;
    for (int j = m; j < h - m; ++j)
        for (int i = m; i < w - m; ++i) mean += double(img.envelope[std::size_t(j * w + i)]) * img.envelope[std::size_t(j * w + i)], ++n;
    mean /= n;
    const auto intensity = [&](int i, int j) {
        const double e = img.envelope[std::size_t(j * w + i)];
        return e * e - mean;
    };
    const auto covariance = [&](int lag) {
        double s = 0;
        int count = 0;
        for (int j = m; j < h - m; ++j)
            for (int i = m; i < w - m; ++i) {
                const int i2 = lateral ? i + lag : i, j2 = lateral ? j : j + lag;
                if (i2 >= w - m || j2 >= h - m) continue;
                s += intensity(i, j) * intensity(i2, j2);
                ++count;
            }
        return s / count;
    };
    const double c0 = covariance(0);
    double previous = 1.0;
    for (int lag = 1; lag < 64; ++lag) {
        const double c = covariance(lag) / c0;
        if (c < 0.5) return 2.0 * pixel_mm * (lag - 1 + (previous - 0.5) / (previous - c));  // linear between the lags
        previous = c;
    }
    return 1e9;
}

// The gates themselves, on an image of homogeneous tissue made with `spec`, 20 pixels in from its
// edges: speckle SNR 1.913 +- 0.1 (Rayleigh), the intensity autocovariance as wide as the PSF within
// 10 %, axially and laterally; the figures printed after `who`.
inline void expect_speckle_gates(const BModeImage& img, const ScanSpec& spec, const char* who)
{
    const double snr = speckle_snr(img, 20);
    const double axial = autocovariance_fwhm_mm(img, 20, false, spec.pixel_mm);
    const double lateral = autocovariance_fwhm_mm(img, 20, true, spec.pixel_mm);
    std::printf("%s: speckle SNR %.3f, autocovariance FWHM axial %.3f mm (PSF %.2f), lateral %.3f mm (PSF %.2f)\n", who, snr, axial,
                spec.axial_fwhm_mm, lateral, spec.lateral_fwhm_mm);
    EXPECT_NEAR(snr, 1.913, 0.1);
    EXPECT_NEAR(axial, spec.axial_fwhm_mm, 0.1 * spec.axial_fwhm_mm);
    EXPECT_NEAR(lateral, spec.lateral_fwhm_mm, 0.1 * spec.lateral_fwhm_mm);
}

}  // namespace echosim::echo::gates

#include "echo/bmode.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

#include <glm/geometric.hpp>

#include "echo/log_compress.hpp"

namespace echosim::echo {
namespace {

using cplx = std::complex<float>;

// Acoustic properties by tissue: scattering strength (relative), impedance [MRayl], attenuation
// [dB/cm/MHz]. Blood barely scatters (anechoic lumen); an acute thrombus is hypo-echoic, a chronic
// one echogenic; bone reflects most of the energy and absorbs the rest.
struct Acoustics {
    float scatter;
    float impedance;
    float attenuation;
};
constexpr std::array<Acoustics, kTissueCount> kAcoustics = {{
    {0.0f, 1.50f, 0.002f},   // outside the skin: the coupling gel (anechoic)
    {1.3f, 1.62f, 1.0f},     // skin
    {0.45f, 1.38f, 0.6f},    // fat
    {1.1f, 1.68f, 0.9f},     // fascia
    {0.7f, 1.70f, 0.9f},     // muscle
    {0.02f, 1.61f, 0.15f},   // artery lumen (blood)
    {1.5f, 1.72f, 1.0f},     // artery wall
    {0.02f, 1.61f, 0.15f},   // vein lumen
    {1.2f, 1.70f, 1.0f},     // vein wall
    {0.12f, 1.63f, 0.3f},    // acute thrombus: hypo-echoic
    {0.02f, 1.61f, 0.15f},   // saphenous lumen
    {2.0f, 7.80f, 20.0f},    // bone cortex
    {0.3f, 1.50f, 10.0f},    // marrow
    {0.9f, 1.68f, 0.6f},     // organised (chronic) thrombus: echogenic
}};
constexpr float kSpecular = 40.0f;  // specular echo relative to a unit scatterer (about 20 dB over speckle)
constexpr double kLattice = 0.1;    // scatterer lattice [mm]

std::uint64_t mix(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

std::uint64_t lattice_key(const glm::dvec3& p, double cell_x, double cell_y, double cell_z, std::uint64_t salt)
{
    const auto i = std::int64_t(std::floor(p.x / cell_x)), j = std::int64_t(std::floor(p.y / cell_y)),
               k = std::int64_t(std::floor(p.z / cell_z));
    return mix(std::uint64_t(i) * 0x100000001b3ull ^ mix(std::uint64_t(j) + salt) ^ mix(std::uint64_t(k) * 31 + 7));
}

// a complex Gaussian scatterer fixed to the body at p
cplx scatterer(const glm::dvec3& p)
{
    const std::uint64_t h = lattice_key(p, kLattice, kLattice, kLattice, 17);
    const double u1 = (double(h >> 11) + 0.5) / 9007199254740992.0;
    const double u2 = double(mix(h) >> 11) / 9007199254740992.0;
    const double r = std::sqrt(-2.0 * std::log(u1));
    return {float(r * std::cos(2 * std::numbers::pi * u2)), float(r * std::sin(2 * std::numbers::pi * u2))};
}

// texture: muscle fibres run along the limb (z), so their strength varies slowly along z and
// quickly across; fat carries thin bright septa
float texture(Tissue t, const glm::dvec3& p)
{
    if (t == Tissue::muscle) {
        const double v = double(lattice_key(p, 0.6, 0.6, 12.0, 3) >> 11) / 9007199254740992.0;
        return float(0.55 + 0.9 * v);
    }
    if (t == Tissue::fat) {
        const double v = double(lattice_key(p, 1.5, 0.4, 6.0, 5) >> 11) / 9007199254740992.0;
        return v > 0.88 ? 3.0f : 1.0f;
    }
    return 1.0f;
}

std::vector<float> gaussian(double fwhm_mm, double pixel_mm)
{
    const double sigma = fwhm_mm / 2.3548 / pixel_mm;
    const int radius = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<float> k(std::size_t(2 * radius + 1));
    for (int i = -radius; i <= radius; ++i) k[std::size_t(i + radius)] = float(std::exp(-0.5 * i * i / (sigma * sigma)));
    return k;
}

}  // namespace

double attenuation_db_cm_mhz(Tissue t) { return kAcoustics[std::size_t(t)].attenuation; }

BModeImage synthesize(const Medium& medium, const Pose& pose, const ScanSpec& spec)
{
    BModeImage img;
    img.width = spec.columns();
    img.height = spec.rows();
    const std::size_t n = std::size_t(img.width) * img.height;
    img.labels.resize(n);
    std::vector<cplx> field(n);
    const glm::dvec3 origin(pose.position), ax(pose.axis_x()), ay(pose.axis_y()), az(pose.axis_z());

    // elevational planes one lattice step apart, weighted by the beam's profile: a probe moved a
    // fraction of a step still sums nearly the same scatterers, so its speckle changes smoothly
    std::vector<std::pair<double, float>> planes;
    const double sigma_e = spec.elevational_fwhm_mm / 2.3548;
    const int reach = int(std::ceil(1.5 * sigma_e / kLattice));
    for (int k = -reach; k <= reach; ++k) {
        const double z = k * kLattice;
        planes.push_back({z, float(std::exp(-0.5 * z * z / (sigma_e * sigma_e)))});
    }

    // 1. scatterers, and the tissue in the image plane
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            const double x = (i + 0.5) * spec.pixel_mm - spec.width_mm / 2, y = (j + 0.5) * spec.pixel_mm;
            const glm::dvec3 p = origin + x * ax + y * ay;
            const std::size_t at = std::size_t(j) * img.width + i;
            const Tissue t = medium.tissue_at(p);
            img.labels[at] = std::uint8_t(t);
            cplx sum = 0;
            for (const auto& [z, w] : planes) sum += w * scatterer(p + z * az);
            float strength = kAcoustics[std::size_t(t)].scatter;
            if (spec.texture) strength *= texture(t, p);
            field[at] = strength * sum;
        }

    // 2-3. down each beam: specular echoes at interfaces, attenuation, shadowing, time-gain
    const double neper_per_db = std::log(10.0) / 20.0;
    for (std::uint32_t i = 0; i < img.width; ++i) {
        double transmitted = 1.0;  // amplitude reaching this depth and coming back, less TGC
        for (std::uint32_t j = 0; j < img.height; ++j) {
            const std::size_t at = std::size_t(j) * img.width + i;
            const auto t = std::size_t(img.labels[at]);
            field[at] *= float(transmitted);
            if (j > 0) {
                const auto u = std::size_t(img.labels[at - img.width]);
                if (u != t) {
                    const float z1 = kAcoustics[u].impedance, z2 = kAcoustics[t].impedance;
                    const double r = std::abs(z2 - z1) / (z2 + z1);
                    field[at] += float(kSpecular * r * transmitted);
                    transmitted *= 1.0 - r * r;  // what is reflected does not go on
                }
            }
            // round trip through this pixel, less the compensation the scanner applies
            const double db = 2.0 * (kAcoustics[t].attenuation - spec.tgc_db_per_cm_mhz) * spec.frequency_mhz * spec.pixel_mm / 10.0;
            transmitted *= std::exp(-db * neper_per_db);
        }
    }

    // 4. point-spread function, separable: axial (down columns), then lateral (along rows)
    const std::vector<float> ka = gaussian(spec.axial_fwhm_mm, spec.pixel_mm), kl = gaussian(spec.lateral_fwhm_mm, spec.pixel_mm);
    const int ra = int(ka.size() / 2), rl = int(kl.size() / 2);
    std::vector<cplx> tmp(n);
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            cplx s = 0;
            for (int d = -ra; d <= ra; ++d) {
                const int jj = int(j) + d;
                if (jj >= 0 && jj < int(img.height)) s += ka[std::size_t(d + ra)] * field[std::size_t(jj) * img.width + i];
            }
            tmp[std::size_t(j) * img.width + i] = s;
        }
    img.envelope.resize(n);
    for (std::uint32_t j = 0; j < img.height; ++j)
        for (std::uint32_t i = 0; i < img.width; ++i) {
            cplx s = 0;
            for (int d = -rl; d <= rl; ++d) {
                const int ii = int(i) + d;
                if (ii >= 0 && ii < int(img.width)) s += kl[std::size_t(d + rl)] * tmp[std::size_t(j) * img.width + std::size_t(ii)];
            }
            img.envelope[std::size_t(j) * img.width + i] = std::abs(s);
        }

    // 5. log compression: a unit-strength scatterer field shows about 20 dB under white
    LogCompressParams params{0, 0, float(spec.gain_db), float(spec.dynamic_range_db)};
    float psf_gain = 0;
    for (float a : ka)
        for (float l : kl) psf_gain += a * a * l * l;
    params.reference = 10.0f * std::sqrt(psf_gain * float(planes.size()));
    const std::vector<std::uint32_t> grey = log_compress_cpu(img.envelope, params);
    img.pixels.resize(n);
    for (std::size_t k = 0; k < n; ++k) img.pixels[k] = std::uint8_t(grey[k] & 0xffu);
    return img;
}

}  // namespace echosim::echo

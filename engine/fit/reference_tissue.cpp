#include "fit/reference_tissue.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "tissue/sample_grid.hpp"

namespace echosim::fit {
namespace {

// strain of one layer under stress sigma: the inverse of sigma = E / beta (exp(beta eps) - 1)
double layer_strain(const Layer& l, double sigma) { return std::log1p(l.beta * sigma / l.modulus) / l.beta; }

}  // namespace

void ReferenceTissue::layers(double u, double v, Layer out[3]) const
{
    const double skin = 1.6 + 0.6 * v;
    const double fat = 5.0 + 13.0 * (0.5 + 0.5 * std::sin(2.4 * u + 1.1) * std::cos(1.7 * v - 0.3));
    const double bone_depth = 36.0 + 16.0 * u + 4.0 * v;
    out[0] = {skin, skin_modulus, skin_beta};
    out[1] = {fat, fat_modulus, fat_beta};
    out[2] = {bone_depth - skin - fat, muscle_modulus, muscle_beta};
}

double ReferenceTissue::column_stress(double depth, double u, double v) const
{
    if (depth <= 0) return 0;
    Layer l[3];
    layers(u, v, l);
    // layers in series carry the same stress; their shortenings add up. Bisection on the stress
    // (the shortening grows monotonically with it).
    double lo = 0, hi = 1.0;
    auto shortening = [&](double s) { return l[0].thickness_mm * layer_strain(l[0], s) + l[1].thickness_mm * layer_strain(l[1], s) +
                                             l[2].thickness_mm * layer_strain(l[2], s); };
    while (shortening(hi) < depth) hi *= 2;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (shortening(mid) < depth ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double ReferenceTissue::indenter_force(double depth, double u, double v) const
{
    if (depth <= 0) return 0;
    const double area = indenter_tip_area + indenter_area_growth * depth;
    const double perimeter = 4.0 * std::sqrt(area);
    return column_stress(depth, u, v) * area + shear * perimeter * depth;
}

double ReferenceTissue::probe_force(const SkinSurface& skin, double depth, double u, double v) const
{
    if (depth <= 0) return 0;
    // the face, 9 x 3 sub-areas; each meets the skin where the curved thigh lies under it
    const glm::dvec3 centre = skin.patch_point(float(u), float(v));
    const glm::dvec3 inward = -glm::dvec3(skin.patch_normal(float(u), float(v)));
    // patch extent [mm] to turn face offsets into patch coordinates
    const double len_u = glm::length(glm::dvec3(skin.patch_point(float(u) + 0.01f, float(v)) - skin.patch_point(float(u) - 0.01f, float(v)))) / 0.02;
    const double len_v = glm::length(glm::dvec3(skin.patch_point(float(u), float(v) + 0.01f) - skin.patch_point(float(u), float(v) - 0.01f))) / 0.02;
    constexpr int nx = 9, nz = 3;
    const double probe_width = probe.face_width_mm, probe_thickness = probe.face_thickness_mm;
    const double cell_area = probe_width * probe_thickness / (nx * nz);
    double force = 0;
    for (int ix = 0; ix < nx; ++ix) {
        const double x = -probe_width / 2 + probe_width * (ix + 0.5) / nx;  // across the thigh (v)
        for (int iz = 0; iz < nz; ++iz) {
            const double z = -probe_thickness / 2 + probe_thickness * (iz + 0.5) / nz;  // along it (u)
            const double uq = u + z / len_u, vq = v + x / len_v;
            const double gap = glm::dot(glm::dvec3(skin.patch_point(float(uq), float(vq))) - centre, inward);
            force += column_stress(depth - gap, uq, vq) * cell_area;
        }
    }
    return force + shear * 2.0 * (probe_width + probe_thickness) * depth;
}

MeasurementSet simulate_campaign(const SkinSurface& skin, const ReferenceTissue& tissue, const CampaignOptions& o)
{
    using tissue::SampleGrid;
    std::mt19937_64 rng(o.seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);

    // the spoiled points: the leg moved by a few millimetres part-way through one probe's sequence
    std::set<int> spoiled;
    while (int(spoiled.size()) < o.spoiled_points) spoiled.insert(int(uniform(rng) * SampleGrid::count) % SampleGrid::count);

    MeasurementSet set;
    std::string made_by = " made by `echosim measure --seed ";
    made_by += std::to_string(o.seed);
    made_by += "` from the reference tissue in engine/fit/reference_tissue.cpp;";
    set.comments = {
        " echosim synthetic force-displacement campaign (paper section 3.1 protocol)",
        made_by,
        " see assets/measurements/README.md. normal = outward skin normal; depth = probe travel into the skin [mm]",
    };
    for (int p = 0; p < SampleGrid::count; ++p) {
        const double u = SampleGrid::u(SampleGrid::row_of(p)), v = SampleGrid::v(SampleGrid::col_of(p));
        const glm::dvec3 position = skin.patch_point(float(u), float(v));
        const glm::dvec3 normal = glm::normalize(glm::dvec3(skin.patch_normal(float(u), float(v))));
        for (ProbeKind probe : {ProbeKind::indenter, ProbeKind::probe}) {
            const double limit = probe == ProbeKind::indenter ? o.indenter_limit_N : o.probe_limit_N;
            // a spoiled point's motion hits one of its two sequences, from a random step on
            double shift = 0;
            int shift_from = o.max_steps + 1;
            if (spoiled.count(p) && (probe == ProbeKind::probe) == (uniform(rng) < 0.5)) {
                shift = (uniform(rng) < 0.5 ? -1.0 : 1.0) * (2.5 + 2.0 * uniform(rng));
                shift_from = 2 + int(uniform(rng) * 4);
            }
            int taken = 0;
            for (int k = 1; k <= o.max_steps; ++k) {
                const double depth = o.step_mm * k;
                const double true_depth = std::max(0.0, depth - (k >= shift_from ? shift : 0.0));
                const double f = probe == ProbeKind::indenter ? tissue.indenter_force(true_depth, u, v)
                                                              : tissue.probe_force(skin, true_depth, u, v);
                if (f > limit) break;
                const double measured = std::max(0.0, f * (1.0 + o.relative_noise * gauss(rng)) + o.absolute_noise_N * gauss(rng));
                set.samples.push_back({p, probe, position, normal, depth, measured});
                ++taken;
            }
            if (taken < 6)
                throw std::runtime_error("synthetic campaign: point " + std::to_string(p) + " (" + to_string(probe) +
                                         ") gave only " + std::to_string(taken) + " samples; the protocol needs 6");
        }
    }
    std::string list = " points spoiled by leg motion:";
    for (int p : spoiled) list.append(" ").append(std::to_string(p));
    set.comments.push_back(list);
    return set;
}

}  // namespace echosim::fit

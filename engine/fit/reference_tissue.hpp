// The "real thigh" of the synthetic measurement campaign (assets/measurements/README.md documents it
// with its true parameters). No real measurements of this kind are public, so we make them; to keep
// the fit an honest approximation problem, as in the paper, the reference is deliberately richer
// than the two-layer model that is fitted to it:
//   - a column of three layers over bone (skin, fat, muscle), each with an exponentially stiffening
//     stress-strain law sigma = E / beta (exp(beta eps) - 1), compressed in series;
//   - layer thicknesses that vary smoothly over the patch (the fat from 5 to 18 mm, the bone deeper
//     distally and anteriorly);
//   - a contact area that depends on the probe: the indenter's pyramidal tip touches more skin the
//     deeper it goes (its effective area grows linearly with depth); the pseudo-probe's flat 40 x 10 mm face meets a curved thigh, so its edges
//     touch later than its centre, and the tissue under it is not uniform;
//   - lateral coupling: the skin around the contact is dragged down with it (a shear ring whose
//     force grows with the contact's perimeter and the depth).
// Units: mm, N, N/mm^2 (MPa).
#pragma once

#include <cstdint>

#include "fit/measurements.hpp"
#include "core/probe_spec.hpp"
#include "core/skin_surface.hpp"

namespace echosim::fit {

struct Layer {
    double thickness_mm;
    double modulus;  // E [N/mm^2]: initial slope of the stress-strain law
    double beta;     // stiffening exponent (dimensionless)
};

struct ReferenceTissue {
    double skin_modulus = 0.12, skin_beta = 2.0;
    double fat_modulus = 0.010, fat_beta = 3.5;
    double muscle_modulus = 0.030, muscle_beta = 4.5;
    double shear = 0.0025;  // lateral coupling [N/mm^2]: force per mm of perimeter per mm of depth
    // the skin spreads the tip's load: the column feels it over an effective area far larger than
    // the tip, which grows as the skin wraps further up the pyramid
    double indenter_tip_area = 120.0;   // [mm^2] effective area at first contact
    double indenter_area_growth = 1.5;  // [mm^2 / mm]
    ProbeSpec probe = kLinearProbe;  // the pseudo-probe has a real probe's face

    // The layers at patch coordinates (u, v).
    void layers(double u, double v, Layer out[3]) const;
    // The compressive stress [N/mm^2] that shortens the column at (u, v) by `depth` [mm].
    double column_stress(double depth, double u, double v) const;

    // Force [N] on each probe pushed `depth` [mm] along the inward normal at patch point (u, v).
    double indenter_force(double depth, double u, double v) const;
    double probe_force(const SkinSurface& skin, double depth, double u, double v) const;
};

struct CampaignOptions {
    std::uint64_t seed = 1;
    double step_mm = 2.0;
    int max_steps = 18;               // the robot's travel: 36 mm
    double indenter_limit_N = 15.0;   // the protocol stops at the first step over the limit
    double probe_limit_N = 40.0;
    double relative_noise = 0.025;    // force sensor noise, standard deviation as a fraction
    double absolute_noise_N = 0.03;
    int spoiled_points = 3;           // points where the leg moved during the measurement
};

// The protocol of §3.1 on the reference: 64 points, two probes, 2 mm steps up to the force limit.
// Throws if a point yields fewer than 6 samples (the protocol's minimum).
MeasurementSet simulate_campaign(const SkinSurface& skin, const ReferenceTissue& tissue, const CampaignOptions& options);

}  // namespace echosim::fit

// Guidance towards the next station (issue 32), from the simulation's truth (STYLE.md 16): where
// the station's vein runs (exam/station_truth.hpp) against where the probe's face is, as a trainee
// is told at the bedside: which way to slide along the leg and how far, how far across, which way
// to turn the probe about its beam to cut the vein transversely, and whether to level it.
//
// Directions: along the leg is the vein's direction turned to point to the head (LPS +z, superior):
// positive towards the groin. Across is the probe's array (+x, the image's right edge). A turn is
// about the beam (+y, into the tissue), positive clockwise as seen from above the skin looking down
// the beam; a vein has no way round, so a turn is within +-90 degrees.
#pragma once

#include <string>

#include "core/pose.hpp"
#include "core/probe_spec.hpp"
#include "exam/scenario.hpp"
#include "exam/station_truth.hpp"
#include "trainer/lesson.hpp"

namespace echosim::trainer {

struct Guidance {
    double along_mm = 0;   // slide along the leg, + towards the groin
    double across_mm = 0;  // slide along the probe's array, + towards the image's right edge
    double turn_deg = 0;   // turn about the beam, + clockwise seen from above
    double tilt_deg = 0;   // the beam from the skin's normal at the station (the ideal probe's beam)
    bool there = false;    // within the scorer's tolerances of the station (along, across, turn)
    double vein_far_mm = 0;  // the vein's far wall under the station's ideal probe, down its beam, at rest
};

Guidance guide(const Pose& probe, const exam::StationTruth& station, const exam::ScoringBands& bands);

// What the guidance shows at a difficulty: the arrow's opacity (0: none), the sentence, its numbers.
struct GuidanceLevel {
    float arrow_alpha = 1;
    bool text = true;
    bool numbers = true;
};
GuidanceLevel guidance_level(Difficulty d);

// The sentence: "Slide 32 mm towards the groin, 6 mm towards the image's left; turn 20 deg
// clockwise." ("At the station: press until the vein closes, then call." when there.) When the
// vein's far wall lies below an image `image_depth_mm` deep, it also says to deepen the image, as a
// sonographer sets the depth before pressing: "The vein lies 61 mm deep: deepen the image (])."
std::string guidance_text(const Guidance& g, const GuidanceLevel& level, double image_depth_mm = kLinearProbe.image_depth_mm);

}  // namespace echosim::trainer

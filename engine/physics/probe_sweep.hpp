// How a probe command reaches the tissue: swept, never jumped. The penalty contact judges a skin
// sample by the probe surface nearest to it, so skin that a probe jumps past in one step (a
// trajectory whose first pose lies 25 mm inside the leg, or a device that glitches) is found nearer
// the probe's sides than its face and is not pushed: the force read 0 N there. The physics thread
// therefore moves its probe towards each command by at most kMaxProbeMoveMm a step (500 mm/s at
// 1 kHz, faster than a hand moves a probe, so a hand's motion is never held back), and a probe
// that appears (inactive before) enters from kProbeEntryMm behind its pose along its beam, deeper
// than any press, so the skin always meets its face first. Each swept step's velocity is its own
// motion, which the contact's damping reads.
#pragma once

#include "contact/probe_contact.hpp"

namespace echosim::physics {

// The most any point of the probe's face moves in one step [mm] (translation plus the rotation's
// sweep at the array's ends).
inline constexpr double kMaxProbeMoveMm = 0.5;
// Where a probe that appears starts, behind its commanded face along the beam [mm]: past the
// deepest press (session::Session::kMaxPressMm, 25 mm) with room.
inline constexpr double kProbeEntryMm = 30.0;

// The probe for the next step of `time_step` [s], from `now` towards `commanded`, moved at most
// `max_move_mm` (a step of several time steps, PhysicsOptions::clear_stride, moves as far as they
// would).
contact::ProbeState swept_probe(const contact::ProbeState& now, const contact::ProbeState& commanded, double time_step,
                                double max_move_mm = kMaxProbeMoveMm);

// Whether no node of the skin at positions `x` (3 per node) lies within `clearance_mm` of the
// probe's face or body: in its frame, across the face's width and thickness widened by the
// clearance, from behind its body to the clearance in front of the face. An inactive probe is
// clear. A few microseconds for the 2,500-node patch, and it writes nothing.
bool probe_clear_by(const contact::ProbeGeometry& geometry, const contact::ProbeState& probe, const Eigen::VectorXd& x,
                    double clearance_mm);

}  // namespace echosim::physics

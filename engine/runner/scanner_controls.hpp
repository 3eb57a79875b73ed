// The scanner's own controls in a running simulator (issue 32, "the scanner a trainee expects"):
// depth, gain and transmit focus, as a scanner's knobs change them, and freeze, which holds the image
// while the trainee looks at it (the probe and the tissue go on). Input sources (the window's keys,
// a test's script) say what was asked for as a ScannerInput; the runner's frame holds the settings
// (image::EchoImageGpu::scanner) and the frozen state (EchoImagePass).
#pragma once

#include <string>

#include "echo/echo_frame.hpp"
#include "runner/frame.hpp"

namespace echosim::runner {

// What was asked for since the last poll.
struct ScannerInput {
    int gain_steps = 0;   // + brighter, - darker, kGainStepDb each
    int focus_steps = 0;  // + deeper, - shallower, kFocusStepMm each
    int depth_steps = 0;  // + deeper, - shallower, kDepthStepMm each (not while frozen: the frozen image keeps its scale)
    bool toggle_freeze = false;
};

inline constexpr double kGainStepDb = 2.0, kMaxGainDb = 20.0;  // within +-20 dB
inline constexpr double kFocusStepMm = 2.5, kFocusMarginMm = 5.0;  // within 5 mm of the top and the bottom
inline constexpr double kDepthStepMm = 10.0;  // a centimetre a step, within the image's depth_range()

// The settings after `in` on an image `depth_mm` deep (gain and focus kept within their ranges).
echo::ScannerSettings adjusted(const echo::ScannerSettings& s, const ScannerInput& in, double depth_mm);
// The image's depth after `steps` from `depth_mm`, kept within [shallowest, deepest].
double adjusted_depth(double depth_mm, int steps, double shallowest, double deepest);

// Applies `in` to the frame's image: its depth (unless frozen), its settings (the focus kept within
// the new depth), and freeze toggled.
void apply(SimulatorFrame& frame, const ScannerInput& in);

// "interpolative image, depth 5.0 cm, gain +4 dB, focus 22.5 mm" and ", FROZEN" when it is: for a title bar or a
// status line (the imaging said, so an instructor knows which image the trainee sees).
std::string scanner_status(SimulatorFrame& frame);

}  // namespace echosim::runner

#include "runner/scanner_controls.hpp"

#include <algorithm>
#include <cstdio>

namespace echosim::runner {

echo::ScannerSettings adjusted(const echo::ScannerSettings& s, const ScannerInput& in, double depth_mm)
{
    echo::ScannerSettings out = s;
    out.gain_db = std::clamp(s.gain_db + kGainStepDb * in.gain_steps, -kMaxGainDb, kMaxGainDb);
    const double shallowest = std::min(kFocusMarginMm, depth_mm / 2), deepest = std::max(depth_mm - kFocusMarginMm, depth_mm / 2);
    out.focus_mm = std::clamp(s.focus_mm + kFocusStepMm * in.focus_steps, shallowest, deepest);
    return out;
}

double adjusted_depth(double depth_mm, int steps, double shallowest, double deepest)
{
    return std::clamp(depth_mm + kDepthStepMm * steps, shallowest, deepest);
}

void apply(SimulatorFrame& frame, const ScannerInput& in)
{
    image::EchoImageGpu& image = frame.echo_image();
    if (in.depth_steps != 0 && !frame.echo_pass().frozen()) {
        const auto [shallowest, deepest] = image.depth_range();
        image.set_depth_mm(adjusted_depth(image.plane().depth_mm, in.depth_steps, shallowest, deepest));
    }
    echo::ScannerSettings& s = image.scanner();
    s = adjusted(s, in, image.plane().depth_mm);
    if (in.toggle_freeze) frame.echo_pass().set_frozen(!frame.echo_pass().frozen());
}

std::string scanner_status(SimulatorFrame& frame)
{
    const echo::ScannerSettings& s = frame.echo_image().scanner();
    char text[128];
    std::snprintf(text, sizeof text, "%s image, depth %.1f cm, gain %+.0f dB, focus %.1f mm%s", echo::imaging_name(frame.echo_image().imaging()),
                  frame.echo_image().plane().depth_mm / 10, s.gain_db, s.focus_mm, frame.echo_pass().frozen() ? ", FROZEN" : "");
    return text;
}

}  // namespace echosim::runner

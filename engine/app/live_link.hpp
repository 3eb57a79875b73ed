// The live link of `echosim run --igtl` (igtl/server.hpp): a frame the window drew and read back,
// with the session's input it was drawn from, made into what the link sends (igtl/live_frame.hpp).
#pragma once

#include <cstdint>
#include <span>

#include "echo/echo_frame.hpp"
#include "igtl/live_frame.hpp"

namespace echosim::app {

// Fills `out` (its pixel storage reused) with the image `grey` (a byte a pixel, as the display shows
// it) of `plane` drawn from `frame`: the image placed where the
// probe's face put it (echo::pixel_to_world, 1 mm thick), the probe's pose, the wall clock.
void fill_live_frame(igtl::LiveFrame& out, const echo::ImagePlane& plane, const echo::EchoFrame& frame, std::span<const std::uint8_t> grey,
                     double wall_clock_s);

}  // namespace echosim::app

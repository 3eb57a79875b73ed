#include "app/live_link.hpp"

#include <stdexcept>
#include <string>

namespace echosim::app {

void fill_live_frame(igtl::LiveFrame& out, const echo::ImagePlane& plane, const echo::EchoFrame& frame, std::span<const std::uint8_t> grey,
                     double wall_clock_s)
{
    if (grey.size() != plane.pixels())
        throw std::invalid_argument("live frame: " + std::to_string(grey.size()) + " pixels read back for a " + std::to_string(plane.columns) +
                                    " x " + std::to_string(plane.rows) + " image");
    out.columns = plane.columns;
    out.rows = plane.rows;
    out.pixels.assign(grey.begin(), grey.end());
    out.image_to_world = echo::pixel_to_world(plane, frame.face);
    out.probe_to_world = glm::dmat4(frame.face.matrix());
    out.timestamp_s = wall_clock_s;
}

}  // namespace echosim::app

#include "app/live_link.hpp"

#include <cstdio>
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

void report_link(igtl::Server& link, std::vector<igtl::ServerEvent>& events, const std::string& lead)
{
    events.clear();
    link.events(events);
    for (const igtl::ServerEvent& e : events) {
        switch (e.kind) {
        case igtl::ServerEvent::Kind::connected:
            std::printf("%sOpenIGTLink: %s connected (%d client%s)\n", lead.c_str(), e.peer.c_str(), e.clients, e.clients == 1 ? "" : "s");
            break;
        case igtl::ServerEvent::Kind::disconnected:
            std::printf("%sOpenIGTLink: %s gone: %s, after %lld frames (%d client%s)\n", lead.c_str(), e.peer.c_str(), e.reason.c_str(),
                        static_cast<long long>(e.frames), e.clients, e.clients == 1 ? "" : "s");
            break;
        case igtl::ServerEvent::Kind::error:
            std::fprintf(stderr, "%sOpenIGTLink: %s\n", lead.c_str(), e.reason.c_str());
            break;
        }
    }
}

void LiveLink::on_attach(runner::Runner& runner)
{
    if (!runner.frame() || !runner.context())
        throw std::invalid_argument("live link: the runner configuration '" + runner.config().name + "' draws no frame to serve");
    runner.frame()->echo_pass().enable_readback(
        *runner.context(),
        [this](const echo::EchoFrame& drawn, const echo::ImagePlane& plane, std::span<const std::uint8_t> grey, double wall_clock_s) {
            fill_live_frame(live_, plane, drawn, grey, wall_clock_s);
            link_.publish(live_);
        });
}

}  // namespace echosim::app

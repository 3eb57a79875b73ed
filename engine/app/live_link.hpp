// The live link of `echosim run --igtl` (igtl/server.hpp): a frame the window drew and read back,
// with the session's input it was drawn from, made into what the link sends (igtl/live_frame.hpp);
// and the runner's observer that serves it (LiveLink).
#pragma once

#include <cstdint>
#include <span>

#include <string>
#include <vector>

#include "echo/echo_frame.hpp"
#include "igtl/live_frame.hpp"
#include "igtl/server.hpp"
#include "runner/runner.hpp"

namespace echosim::app {

// Fills `out` (its pixel storage reused) with the image `grey` (a byte a pixel, as the display shows
// it) of `plane` drawn from `frame`: the image placed where the
// probe's face put it (echo::pixel_to_world, 1 mm thick), the probe's pose, the wall clock.
void fill_live_frame(igtl::LiveFrame& out, const echo::ImagePlane& plane, const echo::EchoFrame& frame, std::span<const std::uint8_t> grey,
                     double wall_clock_s);

// What the link's clients did since the last call, one line each, after `lead` ("echosim run: ").
void report_link(igtl::Server& link, std::vector<igtl::ServerEvent>& events, const std::string& lead);

// The live link as an observer of the runner (runner/runner.hpp): when it joins, the frame's
// echographic image pass reads every frame's image back (a slot behind, no wait:
// runner/echo_image_pass.hpp) and the link publishes it with the pose it was drawn at; every step
// it reports what the link's clients did. `link` must outlive the runner.
class LiveLink final : public runner::Observer {
public:
    LiveLink(igtl::Server& link, std::string lead) : link_(link), lead_(std::move(lead)) {}
    void on_attach(runner::Runner& runner) override;
    void on_step(runner::StepContext&) override { report_link(link_, events_, lead_); }

private:
    igtl::Server& link_;
    std::string lead_;
    igtl::LiveFrame live_;  // its pixel storage reused frame after frame
    std::vector<igtl::ServerEvent> events_;
};

}  // namespace echosim::app

// The scanner's caliper (issue 32): on a frozen image the trainee clicks two points on the image
// panel and reads the distance between them, as a sonographer measures a vein's calibre (a
// distended vein, wider than its artery, is an acute clot's sign; a normal CFV is 10 to 14 mm).
// The points are kept in the image's millimetres, so they stay on the tissue they were put on when
// the window changes size; a third click starts a new measurement, and unfreezing clears it.
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <vulkan/vulkan.h>

#include "echo/echo_frame.hpp"

namespace echosim::trainer {

// Where the echographic image lies in a frame [px from its top left] (runner::echo_panel_rect's
// pixels), and the plane it shows [mm].
struct ImagePanel {
    float x = 0, y = 0, width = 0, height = 0;
    double width_mm = 0, depth_mm = 0;
};
ImagePanel image_panel(VkExtent2D frame, const echo::ImagePlane& plane);

// The image's point under a place in the frame [px, continuous: a pixel's centre at +0.5]: (across,
// from the image's centre line; down, from the probe's face) [mm]; none off the image.
std::optional<glm::dvec2> image_point_at(const ImagePanel& panel, glm::vec2 pixel);
// The frame pixel an image point [mm] is drawn at (image_point_at's inverse).
glm::vec2 pixel_of(const ImagePanel& panel, glm::dvec2 point_mm);

class Caliper {
public:
    // The first point, then the second; a click after both starts a new measurement there.
    void click(glm::dvec2 point_mm);
    void clear();
    const std::optional<glm::dvec2>& first() const { return first_; }
    const std::optional<glm::dvec2>& second() const { return second_; }
    // The distance between the two points [mm], once both are placed.
    std::optional<double> distance_mm() const;

private:
    std::optional<glm::dvec2> first_, second_;
};

}  // namespace echosim::trainer

#include "trainer/caliper.hpp"

#include <glm/geometric.hpp>

#include "runner/frame.hpp"

namespace echosim::trainer {

ImagePanel image_panel(VkExtent2D frame, const echo::ImagePlane& plane)
{
    const VkRect2D px = render::target_pixels(runner::echo_panel_rect(frame, plane), frame);
    return {float(px.offset.x), float(px.offset.y), float(px.extent.width), float(px.extent.height), plane.width_mm, plane.depth_mm};
}

std::optional<glm::dvec2> image_point_at(const ImagePanel& panel, glm::vec2 pixel)
{
    if (panel.width <= 0 || panel.height <= 0) return std::nullopt;
    const double u = (double(pixel.x) - panel.x) / panel.width, v = (double(pixel.y) - panel.y) / panel.height;
    if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return std::nullopt;  // (a NaN is off it too)
    return glm::dvec2((u - 0.5) * panel.width_mm, v * panel.depth_mm);
}

glm::vec2 pixel_of(const ImagePanel& panel, glm::dvec2 point_mm)
{
    return {float(panel.x + (point_mm.x / panel.width_mm + 0.5) * panel.width), float(panel.y + point_mm.y / panel.depth_mm * panel.height)};
}

void Caliper::click(glm::dvec2 point_mm)
{
    if (!first_ || second_) {
        first_ = point_mm;
        second_.reset();
    } else {
        second_ = point_mm;
    }
}

void Caliper::clear()
{
    first_.reset();
    second_.reset();
}

std::optional<double> Caliper::distance_mm() const
{
    if (!first_ || !second_) return std::nullopt;
    return glm::distance(*first_, *second_);
}

}  // namespace echosim::trainer

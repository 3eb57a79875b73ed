// Where on the frame's target a pass draws: a rectangle in fractions of the target's width and
// height, from its top-left corner, so it follows the target through resizes. The image panel
// and the 3-D view beside it share the frame this way.
#pragma once

#include <vulkan/vulkan.h>

namespace echosim::render {

struct TargetRect {
    float x = 0.0f, y = 0.0f, width = 1.0f, height = 1.0f;
};

// The pixels `rect` covers in a target of `extent` (edges rounded to the nearest pixel, clipped
// to the target).
VkRect2D target_pixels(const TargetRect& rect, VkExtent2D extent);

}  // namespace echosim::render

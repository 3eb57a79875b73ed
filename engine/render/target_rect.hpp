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

// Begins dynamic rendering into the target `view` (in COLOR_ATTACHMENT_OPTIMAL, stored) over `area`,
// its colour loaded or cleared as `load` says, with the viewport and scissor on `area`: how a pass
// that draws over part of the frame starts. End it with vkCmdEndRendering.
void begin_rendering_over(VkCommandBuffer cmd, VkImageView view, VkRect2D area, VkAttachmentLoadOp load);

}  // namespace echosim::render

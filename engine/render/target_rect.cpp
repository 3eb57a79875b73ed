#include "render/target_rect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace echosim::render {
namespace {

// a fraction of an edge to a pixel column or row, within [0, size]
std::int64_t edge(float fraction, std::uint32_t size)
{
    return std::clamp<std::int64_t>(std::llround(double(fraction) * double(size)), 0, std::int64_t(size));
}

}  // namespace

VkRect2D target_pixels(const TargetRect& rect, VkExtent2D extent)
{
    const std::int64_t x0 = edge(rect.x, extent.width), x1 = edge(rect.x + rect.width, extent.width);
    const std::int64_t y0 = edge(rect.y, extent.height), y1 = edge(rect.y + rect.height, extent.height);
    return {{std::int32_t(x0), std::int32_t(y0)},
            {std::uint32_t(std::max<std::int64_t>(0, x1 - x0)), std::uint32_t(std::max<std::int64_t>(0, y1 - y0))}};
}

void begin_rendering_over(VkCommandBuffer cmd, VkImageView view, VkRect2D area, VkAttachmentLoadOp load)
{
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = load;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = area;
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &rendering);
    const VkViewport vp{float(area.offset.x), float(area.offset.y), float(area.extent.width), float(area.extent.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &area);
}

}  // namespace echosim::render

#include "gpu/offscreen.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {

namespace {

VkExtent2D checked_extent(const Context& ctx, VkExtent2D extent)
{
    const auto max_dim = ctx.limits().maxImageDimension2D;
    if (extent.width == 0 || extent.height == 0 || extent.width > max_dim || extent.height > max_dim)
        throw std::invalid_argument("image size " + std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                                    " is outside 1.." + std::to_string(max_dim) + " on " + ctx.device_name());
    return extent;
}

// the read-back copies four bytes a pixel in RGBA order
VkFormat checked_format(VkFormat format)
{
    if (format != VK_FORMAT_R8G8B8A8_UNORM && format != VK_FORMAT_R8G8B8A8_SRGB)
        throw std::invalid_argument("offscreen target format " + std::to_string(int(format)) + ": R8G8B8A8_UNORM or R8G8B8A8_SRGB");
    return format;
}

}  // namespace

OffscreenPresenter::OffscreenPresenter(CommandPool& commands, VkExtent2D extent, VkFormat format)
    : ctx_(commands.context()),
      commands_(commands),
      color_(ctx_, checked_extent(ctx_, extent), checked_format(format), kUsage, VK_IMAGE_ASPECT_COLOR_BIT),
      readback_(ctx_, VkDeviceSize(extent.width) * extent.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::host_visible)
{
}

OffscreenPresenter::~OffscreenPresenter() { ctx_.wait_idle(); }

void OffscreenPresenter::render(const FramePasses& passes, io::RgbaImage* out)
{
    commands_.submit_and_wait([&](VkCommandBuffer cmd) { record(cmd, passes, out != nullptr); });
    if (out) {
        out->width = color_.extent().width;
        out->height = color_.extent().height;
        out->pixels.resize(readback_.size());
        std::memcpy(out->pixels.data(), readback_.mapped(), readback_.size());
    }
}

void OffscreenPresenter::record(VkCommandBuffer cmd, const FramePasses& passes, bool readback)
{
    const FrameTarget target{color_.handle(), color_.view(), color_.extent(), color_.format(), kUsage};
    // the last frame's readback is over (its fence was waited for): the image starts as new, and
    // ends as the source of this frame's copy
    const TargetState initial{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE};
    const TargetState final{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
    passes.record(cmd, slot_, target, initial, final);
    slot_ = (slot_ + 1) % kFramesInFlight;

    if (readback) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {target.extent.width, target.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, color_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &region);
        host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    }
}

}  // namespace echosim::gpu

#include "gpu/offscreen.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {

OffscreenPresenter::OffscreenPresenter(const Context& ctx, VkExtent2D extent) : ctx_(ctx)
{
    const auto max_dim = ctx.limits().maxImageDimension2D;
    if (extent.width == 0 || extent.height == 0 || extent.width > max_dim || extent.height > max_dim)
        throw std::invalid_argument("image size " + std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                                    " is outside 1.." + std::to_string(max_dim) + " on " + ctx.device_name());
    color_ = Image(ctx, extent, kFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   VK_IMAGE_ASPECT_COLOR_BIT);
    readback_ = Buffer(ctx, VkDeviceSize(extent.width) * extent.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       MemoryUse::host_visible);

    const VkDevice dev = ctx.device();
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = ctx.queue_family();
    check(vkCreateCommandPool(dev, &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (vkAllocateCommandBuffers(dev, &alloc, &cmd_) != VK_SUCCESS ||
        vkCreateFence(dev, &fence_info, nullptr, &fence_) != VK_SUCCESS) {
        vkDestroyCommandPool(dev, pool_, nullptr);
        throw std::runtime_error("offscreen presenter: cannot allocate a command buffer or fence");
    }
}

OffscreenPresenter::~OffscreenPresenter()
{
    const VkDevice dev = ctx_.device();
    vkQueueWaitIdle(ctx_.queue());
    vkDestroyFence(dev, fence_, nullptr);
    vkDestroyCommandPool(dev, pool_, nullptr);
}

void OffscreenPresenter::render(Renderer& renderer, const FrameView& view, io::RgbaImage* out)
{
    const VkDevice dev = ctx_.device();
    check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");

    RenderTarget target;
    target.image = color_.handle();
    target.view = color_.view();
    target.extent = color_.extent();
    target.final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    target.next_stage = VK_PIPELINE_STAGE_2_COPY_BIT;
    target.next_access = VK_ACCESS_2_TRANSFER_READ_BIT;
    renderer.record(cmd_, 0, target, view);

    if (out) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {target.extent.width, target.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd_, color_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &region);
        // make the copy visible to the host read below
        VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        barrier.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        barrier.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        barrier.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &barrier;
        vkCmdPipelineBarrier2(cmd_, &dep);
    }
    check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

    check(vkResetFences(dev, 1, &fence_), "vkResetFences");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    check(vkQueueSubmit(ctx_.queue(), 1, &submit, fence_), "vkQueueSubmit (offscreen)");
    check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences (offscreen)");

    if (out) {
        out->width = target.extent.width;
        out->height = target.extent.height;
        out->pixels.resize(readback_.size());
        std::memcpy(out->pixels.data(), readback_.mapped(), readback_.size());
    }
}

}  // namespace echosim::gpu

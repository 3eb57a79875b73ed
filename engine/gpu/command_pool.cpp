#include "gpu/command_pool.hpp"

#include <span>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {

CommandPool::CommandPool(const Context& ctx) : ctx_(ctx)
{
    const VkDevice dev = ctx.device();
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = ctx.queue_family();
    check(vkCreateCommandPool(dev, &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    try {
        once_ = allocate();
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "vkCreateFence (command pool)");
    } catch (...) {
        vkDestroyCommandPool(dev, pool_, nullptr);
        throw;
    }
}

CommandPool::~CommandPool()
{
    // the command buffers go with the pool; submit_and_wait left none of them in flight
    vkDestroyFence(ctx_.device(), fence_, nullptr);
    vkDestroyCommandPool(ctx_.device(), pool_, nullptr);
}

VkCommandBuffer CommandPool::allocate()
{
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(ctx_.device(), &alloc, &cmd), "vkAllocateCommandBuffers");
    return cmd;
}

void CommandPool::free(VkCommandBuffer cmd) { vkFreeCommandBuffers(ctx_.device(), pool_, 1, &cmd); }

void CommandPool::submit_and_wait(const std::function<void(VkCommandBuffer)>& record)
{
    const VkDevice dev = ctx_.device();
    check(vkResetCommandBuffer(once_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(once_, &begin), "vkBeginCommandBuffer");
    record(once_);
    check(vkEndCommandBuffer(once_), "vkEndCommandBuffer");

    check(vkResetFences(dev, 1, &fence_), "vkResetFences");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &once_;
    ctx_.submit(std::span(&submit, 1), fence_);
    check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace echosim::gpu

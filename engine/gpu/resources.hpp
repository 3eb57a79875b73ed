// The second Vulkan layer: buffers, images and one-shot command submission on top of a Context.
// Each resource owns its memory (one allocation per resource: echosim holds a few dozen, far below
// maxMemoryAllocationCount) and is move-only; destruction waits for nothing, so the owner must make
// sure the GPU is done with it (the presenters do, by fences).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"

namespace echosim::gpu {

enum class MemoryUse { device_local, host_visible };

class Buffer {
public:
    Buffer() = default;
    Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
    ~Buffer() { reset(); }
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    // Host-visible buffers stay mapped for their whole life (coherent memory: no flush needed).
    void* mapped() const { return mapped_; }
    void write(std::span<const std::byte> bytes, VkDeviceSize offset = 0);

private:
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

class Image {
public:
    Image() = default;
    Image(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect);
    ~Image() { reset(); }
    Image(Image&& o) noexcept { *this = std::move(o); }
    Image& operator=(Image&& o) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    VkExtent2D extent() const { return extent_; }
    VkFormat format() const { return format_; }

private:
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    VkFormat format_ = VK_FORMAT_UNDEFINED;
};

// Records `record` into a fresh command buffer, submits it and waits: for uploads at start-up and
// for tests, never per frame.
void submit_and_wait(const Context& ctx, const std::function<void(VkCommandBuffer)>& record);

// A device-local buffer filled with `bytes` through a staging buffer.
Buffer upload_buffer(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage);

// One image layout transition (synchronization2) covering all mips and layers of a colour or depth image.
void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                VkAccessFlags2 dst_access);

}  // namespace echosim::gpu

// The second Vulkan layer: buffers, images (2-D and 3-D), samplers and uploads through staging on
// top of a Context. Each resource owns its memory (one allocation per resource: echosim holds a few
// dozen, far below maxMemoryAllocationCount) and is move-only; destruction waits for nothing, so the
// owner must make sure the GPU is done with it (the presenters do, by fences; the passes wait for
// the device before theirs go: gpu/frame.hpp, "Lifetime").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/command_pool.hpp"
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
    // A 2-D image (render targets, depth buffers, the echographic image). `swizzle` is its view's
    // (a one-channel grey image read as grey: {R, R, R, ONE}).
    Image(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
          VkComponentMapping swizzle = {});
    // A 3-D colour image (volumes sampled by compute kernels); its view is a 3-D view.
    Image(const Context& ctx, VkExtent3D extent, VkFormat format, VkImageUsageFlags usage);
    ~Image() { reset(); }
    Image(Image&& o) noexcept { *this = std::move(o); }
    Image& operator=(Image&& o) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    VkExtent2D extent() const { return {extent_.width, extent_.height}; }
    VkExtent3D extent3d() const { return extent_; }
    VkImageType type() const { return type_; }
    VkFormat format() const { return format_; }
    VkImageAspectFlags aspect() const { return aspect_; }

private:
    void create(const Context& ctx, VkImageType type, VkExtent3D extent, VkFormat format, VkImageUsageFlags usage,
                VkImageAspectFlags aspect, VkComponentMapping swizzle = {});
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkExtent3D extent_{};
    VkImageType type_ = VK_IMAGE_TYPE_2D;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect_ = 0;
};

// A buffer seen as a one-dimensional array of texels of one format, for `texelFetch` from a
// uniform texel buffer (GLSL `samplerBuffer`): on llvmpipe such a read is one vector gather, where
// a storage buffer's is a loop over the lanes. Throws naming `what` when the device cannot read
// the format so, or the buffer holds more texels than a texel buffer may address.
class TexelView {
public:
    TexelView() = default;
    TexelView(const Context& ctx, const Buffer& buffer, VkFormat format, const char* what);
    ~TexelView() { reset(); }
    TexelView(TexelView&& o) noexcept { *this = std::move(o); }
    TexelView& operator=(TexelView&& o) noexcept;
    TexelView(const TexelView&) = delete;
    TexelView& operator=(const TexelView&) = delete;

    VkBufferView handle() const { return view_; }

private:
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkBufferView view_ = VK_NULL_HANDLE;
};

// How a sampler reads between texels. Every sampler clamps to the edge on all axes and reads
// normalised coordinates, without mip levels: images and volumes are sampled where they are.
enum class Filter { nearest, linear };

class Sampler {
public:
    Sampler() = default;
    Sampler(const Context& ctx, Filter filter);
    ~Sampler() { reset(); }
    Sampler(Sampler&& o) noexcept { *this = std::move(o); }
    Sampler& operator=(Sampler&& o) noexcept;
    Sampler(const Sampler&) = delete;
    Sampler& operator=(const Sampler&) = delete;

    VkSampler handle() const { return sampler_; }
    Filter filter() const { return filter_; }

private:
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
    Filter filter_ = Filter::nearest;
};

// Bytes per texel of the colour formats echosim uploads; throws for any other format.
std::uint32_t texel_bytes(VkFormat format);
// Whether the format is one of the 8-bit sRGB colour formats (sampling decodes, writing encodes).
bool is_srgb(VkFormat format);

// A device-local buffer filled with `bytes` through a staging buffer; waits for the copy.
Buffer upload_buffer(CommandPool& pool, std::span<const std::byte> bytes, VkBufferUsageFlags usage);

// Fills all of a colour image (2-D or 3-D, tightly packed rows and slices, x fastest) with `bytes`
// through a staging buffer, and leaves it in `layout`, ready for compute and fragment shaders to
// read (SHADER_READ_ONLY_OPTIMAL) or write (GENERAL). The image needs TRANSFER_DST usage. Waits.
void upload_image(CommandPool& pool, const Image& image, std::span<const std::byte> bytes,
                  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

// The texels of a whole colour image (2-D or 3-D, packed as upload_image takes them), copied back to
// the host; the image is in `layout` before and after, and needs TRANSFER_SRC usage. Waits.
std::vector<std::byte> download_image(CommandPool& pool, const Image& image, VkImageLayout layout);

// Makes what `src_stage` wrote (`src_access`) visible to the host, once the submission's fence has
// signalled: before the host reads a readback buffer or a host-visible storage buffer.
void host_read_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access);

// Makes what `src_stage` wrote (`src_access`) visible to `dst_stage`'s `dst_access` (one global
// memory barrier): between two dispatches, the second reading the first's buffers.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                    VkAccessFlags2 dst_access);

// One image layout transition (synchronization2) covering all mips and layers of a colour or depth image.
void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                VkAccessFlags2 dst_access);

}  // namespace echosim::gpu

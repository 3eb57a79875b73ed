#include "gpu/resources.hpp"

#include <cstdio>
#include <cstring>
#include <string>
#include <stdexcept>
#include <utility>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {
namespace {

std::string to_hex(std::uint32_t v)
{
    char text[16];
    std::snprintf(text, sizeof text, "%x", v);
    return text;
}

}  // namespace

Buffer::Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
    : device_(ctx.device()), size_(size)
{
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    const auto props = use == MemoryUse::host_visible
                           ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                           : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    try {
        alloc.memoryTypeIndex = ctx.find_memory_type(req.memoryTypeBits, props);
        check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "vkAllocateMemory (buffer)");
        check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
        if (use == MemoryUse::host_visible) check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    } catch (...) {
        reset();
        throw;
    }
}

Buffer& Buffer::operator=(Buffer&& o) noexcept
{
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(o.size_, 0);
        mapped_ = std::exchange(o.mapped_, nullptr);
    }
    return *this;
}

void Buffer::reset()
{
    if (!device_) return;
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);  // unmaps implicitly
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
}

void Buffer::write(std::span<const std::byte> bytes, VkDeviceSize offset)
{
    if (!mapped_) throw std::logic_error("Buffer::write on a buffer that is not host-visible");
    if (offset + bytes.size() > size_) throw std::out_of_range("Buffer::write past the end of the buffer");
    std::memcpy(static_cast<std::byte*>(mapped_) + offset, bytes.data(), bytes.size());
}

Image::Image(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
             VkComponentMapping swizzle)
{
    create(ctx, VK_IMAGE_TYPE_2D, {extent.width, extent.height, 1}, format, usage, aspect, swizzle);
}

Image::Image(const Context& ctx, VkExtent3D extent, VkFormat format, VkImageUsageFlags usage)
{
    create(ctx, VK_IMAGE_TYPE_3D, extent, format, usage, VK_IMAGE_ASPECT_COLOR_BIT);
}

void Image::create(const Context& ctx, VkImageType type, VkExtent3D extent, VkFormat format, VkImageUsageFlags usage,
                   VkImageAspectFlags aspect, VkComponentMapping swizzle)
{
    const std::string kind = type == VK_IMAGE_TYPE_3D ? "a 3-D image" : "an image";
    const std::string size = std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                             (type == VK_IMAGE_TYPE_3D ? "x" + std::to_string(extent.depth) : std::string());
    // ask first, so an unsupported format or size names itself rather than failing as vkCreateImage
    VkImageFormatProperties supported{};
    const VkResult support = vkGetPhysicalDeviceImageFormatProperties(ctx.physical_device(), format, type,
                                                                      VK_IMAGE_TILING_OPTIMAL, usage, 0, &supported);
    if (support != VK_SUCCESS)
        throw VulkanError(support, kind + " of format " + std::to_string(int(format)) + " and usage 0x" +
                                       to_hex(usage) + " on " + ctx.device_name());
    if (extent.width == 0 || extent.height == 0 || extent.depth == 0 || extent.width > supported.maxExtent.width ||
        extent.height > supported.maxExtent.height || extent.depth > supported.maxExtent.depth)
        throw std::invalid_argument(kind + " of size " + size + " is outside what " + ctx.device_name() +
                                    " offers for its format (" + std::to_string(supported.maxExtent.width) + "x" +
                                    std::to_string(supported.maxExtent.height) + "x" +
                                    std::to_string(supported.maxExtent.depth) + ")");

    device_ = ctx.device();
    extent_ = extent;
    type_ = type;
    format_ = format;
    aspect_ = aspect;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = type;
    info.format = format;
    info.extent = extent;
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device_, &info, nullptr, &image_), "vkCreateImage");
    try {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device_, image_, &req);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = ctx.find_memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "vkAllocateMemory (image)");
        check(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory");

        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image_;
        view.viewType = type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.components = swizzle;
        view.subresourceRange = {aspect, 0, 1, 0, 1};
        check(vkCreateImageView(device_, &view, nullptr, &view_), "vkCreateImageView");
    } catch (...) {
        reset();
        throw;
    }
}

Image& Image::operator=(Image&& o) noexcept
{
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
        extent_ = std::exchange(o.extent_, {});
        type_ = std::exchange(o.type_, VK_IMAGE_TYPE_2D);
        format_ = std::exchange(o.format_, VK_FORMAT_UNDEFINED);
        aspect_ = std::exchange(o.aspect_, 0);
    }
    return *this;
}

void Image::reset()
{
    if (!device_) return;
    if (view_) vkDestroyImageView(device_, view_, nullptr);
    if (image_) vkDestroyImage(device_, image_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

Sampler::Sampler(const Context& ctx, Filter filter) : device_(ctx.device()), filter_(filter)
{
    const VkFilter f = filter == Filter::linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = f;
    info.minFilter = f;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = 0.0f;
    check(vkCreateSampler(device_, &info, nullptr, &sampler_), "vkCreateSampler");
}

Sampler& Sampler::operator=(Sampler&& o) noexcept
{
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
        filter_ = o.filter_;
    }
    return *this;
}

void Sampler::reset()
{
    if (device_ && sampler_) vkDestroySampler(device_, sampler_, nullptr);
    sampler_ = VK_NULL_HANDLE;
}

TexelView::TexelView(const Context& ctx, const Buffer& buffer, VkFormat format, const char* what) : device_(ctx.device())
{
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &props);
    if ((props.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT) == 0)
        throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                          std::string(what) + ": reading format " + std::to_string(int(format)) + " as a texel buffer");
    const VkDeviceSize texels = buffer.size() / texel_bytes(format);
    if (texels > ctx.limits().maxTexelBufferElements)
        throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED, std::string(what) + ": a texel buffer of " + std::to_string(texels) +
                                                             " texels (the device addresses " +
                                                             std::to_string(ctx.limits().maxTexelBufferElements) + ")");
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = buffer.handle();
    info.format = format;
    info.range = VK_WHOLE_SIZE;
    check(vkCreateBufferView(device_, &info, nullptr, &view_), (std::string("vkCreateBufferView (") + what + ")").c_str());
}

TexelView& TexelView::operator=(TexelView&& o) noexcept
{
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    }
    return *this;
}

void TexelView::reset()
{
    if (device_ && view_) vkDestroyBufferView(device_, view_, nullptr);
    view_ = VK_NULL_HANDLE;
}

bool is_srgb(VkFormat f)
{
    return f == VK_FORMAT_R8_SRGB || f == VK_FORMAT_R8G8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB;
}

std::uint32_t texel_bytes(VkFormat format)
{
    switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT: return 1;
    case VK_FORMAT_R16_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UINT: return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB: return 4;
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw std::invalid_argument("texel size of Vulkan format " + std::to_string(int(format)) + " is not known to echosim");
    }
}

namespace {

VkDeviceSize image_bytes(const Image& image)
{
    const VkExtent3D e = image.extent3d();
    return VkDeviceSize(e.width) * e.height * e.depth * texel_bytes(image.format());
}

VkBufferImageCopy whole_image(const Image& image)
{
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = image.extent3d();
    return region;
}

// the stages that may read or write an image after an upload, or before a download
constexpr VkPipelineStageFlags2 kShaderStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

Buffer upload_buffer(CommandPool& pool, std::span<const std::byte> bytes, VkBufferUsageFlags usage)
{
    const Context& ctx = pool.context();
    Buffer staging(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::host_visible);
    staging.write(bytes);
    Buffer target(ctx, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::device_local);
    pool.submit_and_wait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, bytes.size()};
        vkCmdCopyBuffer(cmd, staging.handle(), target.handle(), 1, &region);
    });
    return target;
}

void upload_image(CommandPool& pool, const Image& image, std::span<const std::byte> bytes, VkImageLayout layout)
{
    if (image.aspect() != VK_IMAGE_ASPECT_COLOR_BIT) throw std::invalid_argument("upload_image: only colour images are uploaded");
    if (bytes.size() != image_bytes(image))
        throw std::invalid_argument("upload_image: " + std::to_string(bytes.size()) + " bytes for an image of " +
                                    std::to_string(image_bytes(image)) + " bytes");
    Buffer staging(pool.context(), bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::host_visible);
    staging.write(bytes);
    pool.submit_and_wait([&](VkCommandBuffer cmd) {
        // what the image held before is discarded: the copy writes all of it
        transition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkBufferImageCopy region = whole_image(image);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        transition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kShaderStages,
                   VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);
    });
}

std::vector<std::byte> download_image(CommandPool& pool, const Image& image, VkImageLayout layout)
{
    if (image.aspect() != VK_IMAGE_ASPECT_COLOR_BIT) throw std::invalid_argument("download_image: only colour images are read back");
    if (layout == VK_IMAGE_LAYOUT_UNDEFINED) throw std::invalid_argument("download_image: an image in no layout has nothing to read");
    Buffer readback(pool.context(), image_bytes(image), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::host_visible);
    pool.submit_and_wait([&](VkCommandBuffer cmd) {
        transition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   kShaderStages | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        const VkBufferImageCopy region = whole_image(image);
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &region);
        transition(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, kShaderStages, VK_ACCESS_2_NONE);
        host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    std::vector<std::byte> out(readback.size());
    std::memcpy(out.data(), readback.mapped(), out.size());
    return out;
}

void host_read_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access)
{
    memory_barrier(cmd, src_stage, src_access, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                    VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = src_stage;
    barrier.srcAccessMask = src_access;
    barrier.dstStageMask = dst_stage;
    barrier.dstAccessMask = dst_access;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                VkAccessFlags2 dst_access)
{
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = src_stage;
    barrier.srcAccessMask = src_access;
    barrier.dstStageMask = dst_stage;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace echosim::gpu

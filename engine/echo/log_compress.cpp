#include "echo/log_compress.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "echosim_compute_shaders.hpp"

namespace echosim::echo {

std::uint32_t log_compress_pixel(float envelope, const LogCompressParams& p)
{
    const float amplitude = std::max(envelope, 1e-20f);
    const float db = 20.0f * std::log10(amplitude / p.reference) + p.gain_db;
    const float level = std::clamp((db + p.dynamic_range_db) / p.dynamic_range_db, 0.0f, 1.0f);
    const auto grey = std::uint32_t(level * 255.0f + 0.5f);
    return grey | (grey << 8) | (grey << 16) | (255u << 24);
}

std::vector<std::uint32_t> log_compress_cpu(std::span<const float> envelope, LogCompressParams params)
{
    std::vector<std::uint32_t> out(envelope.size());
    std::transform(envelope.begin(), envelope.end(), out.begin(), [&](float e) { return log_compress_pixel(e, params); });
    return out;
}

LogCompressGpu::LogCompressGpu(const gpu::Context& ctx, std::uint32_t max_pixels)
    : ctx_(ctx),
      kernel_(ctx, kernels::log_compress_comp, "log_compress.comp", 2, sizeof(LogCompressParams)),
      envelope_(ctx, VkDeviceSize(max_pixels) * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::host_visible),
      image_(ctx, VkDeviceSize(max_pixels) * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::host_visible),
      max_pixels_(max_pixels)
{
    const gpu::Buffer* buffers[2] = {&envelope_, &image_};
    kernel_.bind(buffers);
}

std::vector<std::uint32_t> LogCompressGpu::run(std::span<const float> envelope, LogCompressParams params)
{
    if (envelope.size() > max_pixels_)
        throw std::invalid_argument("log compression of " + std::to_string(envelope.size()) + " pixels, buffers hold " +
                                    std::to_string(max_pixels_));
    params.pixel_count = std::uint32_t(envelope.size());
    envelope_.write(std::as_bytes(envelope));
    const std::uint32_t groups = (params.pixel_count + LOG_COMPRESS_GROUP_SIZE - 1) / LOG_COMPRESS_GROUP_SIZE;
    gpu::submit_and_wait(ctx_, [&](VkCommandBuffer cmd) {
        kernel_.record(cmd, std::as_bytes(std::span(&params, 1)), groups);
        // the host reads the result after the fence
        VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        barrier.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        barrier.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &barrier;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    std::vector<std::uint32_t> out(envelope.size());
    std::memcpy(out.data(), image_.mapped(), out.size() * sizeof(std::uint32_t));
    return out;
}

}  // namespace echosim::echo

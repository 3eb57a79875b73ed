#include "image/log_compress_gpu.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "echosim_compute_shaders.hpp"

namespace echosim::image {
namespace {

static_assert(LOG_COMPRESS_ENVELOPE_BINDING == 0 && LOG_COMPRESS_IMAGE_BINDING == 1, "bindings in the order declared below");
constexpr int kSlot = 0;  // run() waits for every dispatch, so one slot serves

}  // namespace

LogCompressGpu::LogCompressGpu(const gpu::Context& ctx, std::uint32_t max_pixels)
    : envelope_(ctx, VkDeviceSize(max_pixels) * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::host_visible),
      image_(ctx, VkDeviceSize(max_pixels) * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::host_visible),
      max_pixels_(max_pixels),
      kernel_(ctx, kernels::log_compress_comp, "log_compress.comp",
              {gpu::BindingKind::storage_buffer, gpu::BindingKind::storage_buffer}, sizeof(kernels::LogCompressParams))
{
    kernel_.bind(kSlot, {gpu::Binding::storage(envelope_), gpu::Binding::storage(image_)});
}

std::vector<std::uint32_t> LogCompressGpu::run(gpu::CommandPool& pool, std::span<const float> envelope,
                                               kernels::LogCompressParams params)
{
    if (envelope.size() > max_pixels_)
        throw std::invalid_argument("log compression of " + std::to_string(envelope.size()) + " pixels, buffers hold " +
                                    std::to_string(max_pixels_));
    params.pixel_count = std::uint32_t(envelope.size());
    envelope_.write(std::as_bytes(envelope));
    pool.submit_and_wait([&](VkCommandBuffer cmd) {
        kernel_.record(cmd, kSlot, std::as_bytes(std::span(&params, 1)), gpu::Groups::cover(params.pixel_count, LOG_COMPRESS_GROUP_SIZE));
        gpu::host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    });
    std::vector<std::uint32_t> out(envelope.size());
    std::memcpy(out.data(), image_.mapped(), out.size() * sizeof(std::uint32_t));
    return out;
}

}  // namespace echosim::image

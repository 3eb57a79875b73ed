// The GPU half of the log-compression stage (the post stage of the echographic image): runs the
// compute kernel compute/log_compress.comp. The CPU reference it must agree with is
// engine/echo/log_compress.hpp; tests run both and compare.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/command_pool.hpp"
#include "gpu/compute.hpp"
#include "log_compress_bindings.h"

namespace echosim::image {

class LogCompressGpu {
public:
    // Buffers for images of up to `max_pixels`, host-visible (the envelope is written, the image
    // read, by the host).
    LogCompressGpu(const gpu::Context& ctx, std::uint32_t max_pixels);

    // Compresses `envelope` and waits for the result, submitting through `pool` (the calling
    // thread's); `params.pixel_count` is set from the envelope's size.
    std::vector<std::uint32_t> run(gpu::CommandPool& pool, std::span<const float> envelope, kernels::LogCompressParams params);

private:
    gpu::Buffer envelope_;
    gpu::Buffer image_;
    std::uint32_t max_pixels_;
    // last, so destroyed first: it waits for the device before the buffers it binds go
    // (gpu/frame.hpp, "Lifetime")
    gpu::ComputeKernel kernel_;
};

}  // namespace echosim::image

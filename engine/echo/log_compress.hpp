// Log compression, the last (post) stage of the echographic image: envelope amplitude to 8-bit
// grey over a dynamic range in dB. Runs as the compute kernel compute/log_compress.comp; the CPU
// function here is the reference the tests compare it with (and the `--cpu` path).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/compute.hpp"
#include "log_compress_bindings.h"

namespace echosim::echo {

using kernels::LogCompressParams;

// Grey level for one envelope sample, exactly as the kernel computes it, packed as RGBA8 (alpha 255).
std::uint32_t log_compress_pixel(float envelope, const LogCompressParams& params);
std::vector<std::uint32_t> log_compress_cpu(std::span<const float> envelope, LogCompressParams params);

class LogCompressGpu {
public:
    LogCompressGpu(const gpu::Context& ctx, std::uint32_t max_pixels);
    std::vector<std::uint32_t> run(std::span<const float> envelope, LogCompressParams params);

private:
    const gpu::Context& ctx_;
    gpu::ComputeKernel kernel_;
    gpu::Buffer envelope_;
    gpu::Buffer image_;
    std::uint32_t max_pixels_;
};

}  // namespace echosim::echo

// Log compression, the last (post) stage of the echographic image: envelope amplitude to 8-bit
// grey over a dynamic range in dB. Runs as the compute kernel compute/log_compress.comp (driven by
// engine/image/log_compress_gpu.hpp); the CPU function here is the reference the tests compare it
// with (and the `--cpu` path). Both read the parameters from the kernel's bindings header.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "log_compress_bindings.h"

namespace echosim::echo {

using kernels::LogCompressParams;

// Grey level for one envelope sample, exactly as the kernel computes it, packed as RGBA8 (alpha 255).
std::uint32_t log_compress_pixel(float envelope, const LogCompressParams& params);
std::vector<std::uint32_t> log_compress_cpu(std::span<const float> envelope, LogCompressParams params);

}  // namespace echosim::echo

#include "echo/log_compress.hpp"

#include <algorithm>
#include <cmath>

namespace echosim::echo {

std::uint32_t log_compress_pixel(float envelope, const LogCompressParams& p)
{
    const float amplitude = std::max(envelope, 1e-20f);
    const float db = 20.0f * std::log10(amplitude / p.reference) + p.gain_db;
    const std::uint32_t grey = kernels::display_grey(db, p.dynamic_range_db);
    return grey | (grey << 8) | (grey << 16) | (255u << 24);
}

std::vector<std::uint32_t> log_compress_cpu(std::span<const float> envelope, LogCompressParams params)
{
    std::vector<std::uint32_t> out(envelope.size());
    std::transform(envelope.begin(), envelope.end(), out.begin(), [&](float e) { return log_compress_pixel(e, params); });
    return out;
}

}  // namespace echosim::echo

#include "echo/post_cpu.hpp"

#include <stdexcept>

namespace echosim::echo {

std::vector<std::uint32_t> post_cpu(std::span<const float> grey, std::span<const float> gain, const kernels::PostParams& p)
{
    const std::size_t n = std::size_t(p.columns) * p.rows;
    const bool warped = (p.flags & POST_WARPED) != 0u;
    if (grey.size() != n || (warped && gain.size() != n)) throw std::invalid_argument("post: the inputs do not match the image");
    std::vector<std::uint32_t> out(n);
    for (std::uint32_t r = 0; r < p.rows; ++r)
        for (std::uint32_t c = 0; c < p.columns; ++c) {
            const std::size_t i = std::size_t(r) * p.columns + c;
            const std::uint32_t g = kernels::post_grey(c, r, grey[i], warped ? gain[i] : 0.0f, p);
            out[i] = g | (g << 8) | (g << 16) | (255u << 24);
        }
    return out;
}

}  // namespace echosim::echo

// The CPU twin of the post kernel (compute/post.comp): the same per-pixel maths (post_grey in
// compute/post_bindings.h), packed as RGBA8 grey with alpha 255.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "post_bindings.h"

namespace echosim::echo {

// `grey`: the slice stage's output; `map`: the deform map (2 floats per pixel), read when
// params.flags has POST_WARPED.
std::vector<std::uint32_t> post_cpu(std::span<const float> grey, std::span<const float> map, const kernels::PostParams& params);

}  // namespace echosim::echo

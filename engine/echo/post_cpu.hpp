// The CPU twin of the post stage, which the slice kernel runs on each sample (compute/slice.comp):
// the same per-pixel maths (post_grey in compute/post_bindings.h), packed as RGBA8 grey with alpha
// 255.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "post_bindings.h"

namespace echosim::echo {

// `grey`, `gain`: the slice stage's output (SliceOutput); `gain` is read when params.flags has
// POST_WARPED.
std::vector<std::uint32_t> post_cpu(std::span<const float> grey, std::span<const float> gain, const kernels::PostParams& params);

}  // namespace echosim::echo

// One image sliced out of a volume at a probe pose (paper §6): the CPU reference of the image
// pipeline's slice stage, used to validate reconstructions against images synthesised directly.
// Grey values are sampled trilinearly, labels by nearest voxel; outside the volume both are 0.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/pose.hpp"
#include "echo/bmode.hpp"
#include "io/nrrd.hpp"
#include "slice_bindings.h"

namespace echosim::echo {

std::vector<std::uint8_t> slice_grey(const io::Volume& volume, const Pose& pose, const ScanSpec& spec);
std::vector<std::uint8_t> slice_labels(const io::Volume& labels, const Pose& pose, const ScanSpec& spec);

// The CPU twin of the slice kernel's sampling (compute/slice.comp; its post stage is post_cpu):
// grey 0..255 per pixel, sampled trilinearly (in float, as the sampler does) where the deform map
// says (params.flags & SLICE_WARPED: `map` holds 2 floats per map entry, map_columns x rows, read
// between columns as map_tap says) or at the pixel's own depth; and, with SLICE_LABELS, the tissue
// codes at the nearest voxel of `labels` (sharing the volume's grid).
struct SliceOutput {
    std::vector<float> grey;
    std::vector<float> gain;  // [dB] per pixel, from the map (warped only)
    std::vector<std::uint8_t> labels;
};
SliceOutput slice_stage_cpu(const io::Volume& volume, const io::Volume* labels, std::span<const float> map,
                            const kernels::SliceParams& params);

// Where pixel (c, r) of a frame samples, as the slice kernel and the live B-mode kernel
// (compute/bmode_live.comp) read it: its lateral position `x` [mm], the deform map's entry between
// its map columns (source depth [mm], gain [dB]; the pixel's own depth and 0 dB unwarped), and that
// point as a continuous voxel index. `map` as slice_stage_cpu's (checked there).
struct SliceSample {
    float x;
    glm::vec2 map;
    glm::vec3 index;
};
SliceSample slice_sample(const kernels::SliceParams& params, std::span<const float> map, std::uint32_t c, std::uint32_t r);
// The tissue code of `labels` (uint8) at the voxel nearest a continuous index; 0 outside.
std::uint8_t label_at(const io::Volume& labels, const glm::vec3& index);

// Image similarity over the pixels where `mask` is non-zero (all when empty).
double normalised_cross_correlation(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                                    const std::vector<std::uint8_t>& mask = {});
double psnr_db(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, const std::vector<std::uint8_t>& mask = {});

}  // namespace echosim::echo

// Bindings of compute/slice.comp, the slice stage of the echographic image (paper §6): the grey
// level at each pixel of the probe's image plane, sampled trilinearly from the volume, at the depth
// the deform stage maps the pixel back to (or at its own depth, undeformed); labels by nearest voxel
// when asked. Shared with its CPU twin (engine/echo/slice_cpu.cpp) and its dispatcher
// (engine/image/echo_image_gpu.cpp).
#ifndef ECHOSIM_SLICE_BINDINGS_H
#define ECHOSIM_SLICE_BINDINGS_H

#include "kernel_shared.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

#define SLICE_GROUP_X 16
#define SLICE_GROUP_Y 8
#define SLICE_VOLUME_BINDING 0  // sampler3D, linear: grey levels (UNORM8)
#define SLICE_LABELS_BINDING 1  // usampler3D, nearest: tissue codes (a 1-voxel map of 0 without labels)
#define SLICE_MAP_BINDING 2     // vec2 per pixel from the deform stage (read when SLICE_WARPED)
#define SLICE_GREY_BINDING 3    // float per pixel: grey level 0..255 (0 outside the volume)
#define SLICE_LABEL_OUT_BINDING 4  // uint per pixel: tissue code (written when SLICE_LABELS)

#define SLICE_WARPED 1u  // sample where the deform map says, not at the pixel's own depth
#define SLICE_LABELS 2u  // also write the labels

struct SliceParams {
    mat4 probe_to_index;  // pressed probe frame [mm] -> volume voxel index (the labels share its grid)
    uint columns;
    uint rows;
    float pixel_x_mm;
    float pixel_y_mm;
    float width_mm;
    uint flags;  // SLICE_WARPED | SLICE_LABELS
    uint pad0;
    uint pad1;
};

// Whether a continuous voxel index lies where trilinear sampling has all eight neighbours (the CPU
// reference's rule: outside, the image is black).
KERNEL_FN bool inside_volume(vec3 index, vec3 size)
{
    return index.x >= 0.0f && index.y >= 0.0f && index.z >= 0.0f && index.x <= size.x - 1.0f && index.y <= size.y - 1.0f &&
           index.z <= size.z - 1.0f;
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif

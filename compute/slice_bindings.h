// Bindings of compute/slice.comp, the slice stage of the echographic image (paper §6): the grey
// level at each pixel of the probe's image plane, sampled trilinearly from the volume, at the depth
// the deform stage maps the pixel back to (or at its own depth, undeformed); labels by nearest voxel
// when asked. The post stage (post_bindings.h: gain, TGC, dynamic range, markers) runs in the same
// invocation, on the sample it has just taken, and the displayed grey levels leave as bytes packed
// four to a word: on llvmpipe every store to memory is a loop over the SIMD lanes, so a separate
// post dispatch (a float stored and loaded again per pixel) and a 32-bit RGBA texel per pixel cost
// more than the sampling itself. Shared with its CPU twins (engine/echo/slice_cpu.cpp,
// engine/echo/post_cpu.cpp) and its dispatcher (engine/image/echo_image_gpu.cpp).
#ifndef ECHOSIM_SLICE_BINDINGS_H
#define ECHOSIM_SLICE_BINDINGS_H

#include "post_bindings.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

// The pixels of a row one invocation takes, and the words of the displayed image they fill: stored
// at once, as llvmpipe makes of every storage-buffer store a loop over the SIMD lanes (the words, a
// vector's components, within one loop). 8 pixels (two words) ran the slice alone faster than 4 (one
// word) in 12 of 13 alternated pairs of runs, by up to 38 %; 16 no faster than 8 (bench/RESULTS.md).
#define SLICE_RUN 8
#define SLICE_RUN_WORDS (SLICE_RUN / 4)
#define SLICE_GROUP_X 16  // invocations, each SLICE_RUN columns
#define SLICE_GROUP_Y 8
#define SLICE_VOLUME_BINDING 0  // sampler3D, linear: grey levels (UNORM8)
#define SLICE_LABELS_BINDING 1  // usampler3D, nearest: tissue codes (a 1-voxel map of 0 without labels)
#define SLICE_MAP_BINDING 2     // texel buffer, RG32F: the deform map, map_columns x rows (read when SLICE_WARPED)
#define SLICE_GREY_BINDING 3    // float per pixel: grey level 0..255, 0 outside the volume (written when SLICE_GREY)
#define SLICE_LABEL_OUT_BINDING 4  // uint per pixel: tissue code (written when SLICE_LABELS)
#define SLICE_DISPLAY_BINDING 5    // uvec2 per run: displayed grey bytes, first pixel lowest; slice_words(columns) words a row
#define SLICE_FRAME_BINDING 6      // uniform: SliceFrame
#define SLICE_ROWS_BINDING 7       // texel buffer, RGBA32F: post_row(r) of each row (post_bindings.h), made by the host
#define SLICE_GENERATED_BINDING 8  // texel buffer, R8UI: a generated image's grey bytes, rows of (columns + 3) / 4 words (read when SLICE_GENERATED)

#define SLICE_WARPED 1u  // sample where the deform map says, not at the pixel's own depth
#define SLICE_LABELS 2u  // also write the labels
#define SLICE_GREY 4u    // also write the sliced grey levels
#define SLICE_POST 8u    // the displayed bytes go through the post stage (else: the sliced grey, rounded)
#define SLICE_PACKED 16u // the volume is RGBA8 texels of 2 x 2 neighbours in (y, z) (below); else R8 through the trilinear sampler
#define SLICE_GENERATED 32u  // the grey levels are a live B-mode image's (bmode_live.comp), not the volume's: the post stage only, no deform gain
#define SLICE_TAPS_SHIFT 8u  // with SLICE_WARPED: the map columns a run reads, slice_taps (4 bits from here)

struct SliceParams {
    mat4 probe_to_index;  // pressed probe frame [mm] -> volume voxel index (the labels share its grid)
    uint columns;
    uint rows;
    float pixel_x_mm;
    float pixel_y_mm;
    float width_mm;
    uint flags;  // SLICE_WARPED | SLICE_LABELS | SLICE_GREY | SLICE_POST | SLICE_PACKED: the kernel's variant
    uint map_columns;  // the deform map's columns across the same width (deform_bindings.h), at most `columns`
    float map_step;    // map_columns / columns: the map's columns per image column, at most 1
    uint volume_x;     // the volume's voxels along each axis (a packed volume's image is another shape)
    uint volume_y;
    uint volume_z;
    uint fold_bits;    // a packed volume's folds (packed_texel): at most 2^fold_bits
};

// A frame's parameters of the fused slice and post stages (a uniform buffer: more than push
// constants are sure to hold).
struct SliceFrame {
    SliceParams slice;
    PostParams post;
};

// A packed volume (SLICE_PACKED): texel (x, y, z) holds the grey levels of (y, z), (y + 1, z),
// (y, z + 1), (y + 1, z + 1) at x, clamped at the far edges, so a trilinear sample is the texels
// at x and x + 1 and the lerps. Made on CPU devices (image::EchoVolumeGpu says when): llvmpipe's
// trilinear filter gathers eight texels per sample and costs several times two plain fetches; a
// GPU's sampler does it in hardware, from a quarter of the memory. The two texels are neighbours in
// memory 3 times in 4 (packed_texel below), so a sample mostly reads one cache line.
//
// Where the texels lie (packed_texel): each row of the image holds four rows of the volume's y in
// tiles of 4 x 4 (x, y), x fastest. llvmpipe lays an image out linearly (x fastest), so a 64-byte
// cache line is one tile, where a plain layout gave a line 16 texels of one row: a plane through
// the volume that is not its (x, y) plane crossed into a new line every few texels (an oblique
// 0.1 mm slice ran at 60 % of a nearly aligned one). An image row holds at most SLICE_TILES_A_ROW
// tiles (an image can be 2048 texels wide where a device allows no more); a wider volume's further
// tiles fold into the rows between, 2^fold_bits rows for each four of y. Shifts and masks only:
// this runs twice a pixel, and a multiply there cost the slice 5 %.
#define SLICE_TILES_A_ROW 128u  // 4 x 4 tiles a row of a packed volume's image at most (2048 texels)
#define SLICE_TILES_A_ROW_BITS 7u

// The fold_bits of a packed volume `voxels_x` wide: 2^fold_bits folds hold its tiles.
KERNEL_FN uint packed_fold_bits(uint voxels_x)
{
    uint tiles = (voxels_x + 3u) >> 2u, bits = 0u;
    while ((SLICE_TILES_A_ROW << bits) < tiles) ++bits;
    return bits;
}

// Where texel `at` of a packed volume lies in its image; fold_bits is SliceParams::fold_bits.
KERNEL_FN uvec3 packed_texel(uvec3 at, uint fold_bits)
{
    uint tile = at.x >> 2u;
    uint u = ((tile & (SLICE_TILES_A_ROW - 1u)) << 4u) | (at.x & 3u) | ((at.y & 3u) << 2u);
    return uvec3(u, ((at.y >> 2u) << fold_bits) | (tile >> SLICE_TILES_A_ROW_BITS), at.z);
}

KERNEL_FN float packed_trilinear(vec4 near_x, vec4 far_x, vec3 f)
{
    vec4 at_x = mix(near_x, far_x, f.x);  // the (y, z) square's corners at x + f.x
    vec2 at_y = mix(vec2(at_x.x, at_x.z), vec2(at_x.y, at_x.w), f.y);
    return mix(at_y.x, at_y.y, f.z);
}

// Where pixel column c reads the deform map, which has map_columns columns across the image's
// width: the map columns either side of the pixel's lateral position, and the right one's weight.
// The position is one product, (c + 1/2) map_step - 1/2 (the map's centres and the image's agree at
// the edges), so neighbouring pixels' taps never lie further apart than their columns do: the
// SLICE_RUN pixels of a run read at most SLICE_RUN + 1 map columns from their first one's left
// (exactly the pixel's own columns when the map is as fine as the image, map_step 1).
struct MapTap {
    uint left;
    uint right;
    float right_weight;
};
KERNEL_FN MapTap map_tap(uint c, SliceParams p)
{
    float last = float(p.map_columns - 1u);
    float u = clamp((float(c) + 0.5f) * p.map_step - 0.5f, 0.0f, last);
    MapTap t;
    t.left = min(uint(u), p.map_columns - 1u);
    t.right = min(t.left + 1u, p.map_columns - 1u);
    t.right_weight = u - float(t.left);
    return t;
}

// The map columns a run reads at most: its pixels' left columns lie at most ceil((SLICE_RUN - 1)
// map_step) apart (map_tap), and the last one's right column is one further. A warped pipeline is
// made for this many (its flags' SLICE_TAPS_SHIFT bits), so its runs fetch and pick among no more
// than they need: 3 for a 1024-column image over 134 map columns, SLICE_RUN + 1 when the map is as
// fine as the image (the margin keeps a float rounding of the product from costing a column).
KERNEL_FN uint slice_taps(float map_step)
{
    return min(uint(SLICE_RUN) + 1u, uint(ceil(float(SLICE_RUN - 1) * map_step + 1e-3f)) + 2u);
}

// The flags of a warped frame's slice pipeline over a map of `map_step` (its dispatcher's, which
// prepares that pipeline before the first pressed frame and must name the same one then).
KERNEL_FN uint slice_warped_flags(float map_step) { return SLICE_WARPED | (slice_taps(map_step) << SLICE_TAPS_SHIFT); }

// The deform map between two of its columns (map_tap's), lerped; but where the two columns' sources
// lie further apart than a smooth field puts neighbours (SLICE_MAP_JUMP_MM), they straddle a closed
// lumen's meeting walls, one column mapping above it and the other below: a lerp would land in the
// closed lumen and draw a dark seam where the walls meet, so the nearer column's source serves.
// The gain is lerped there too: it belongs to the beam, which varies smoothly across (the deform
// stage blends it so), and the walls' one echo (its gain) then runs from one column's meeting point
// to the next's instead of stepping at the middle between them.
#define SLICE_MAP_JUMP_MM 1.0f
KERNEL_FN vec2 map_between(vec2 left, vec2 right, float right_weight)
{
    vec2 lerped = mix(left, right, right_weight);
    if (abs(left.x - right.x) > SLICE_MAP_JUMP_MM) return vec2(right_weight < 0.5f ? left.x : right.x, lerped.y);
    return lerped;
}

// The runs, and the words, a row of the displayed image takes.
KERNEL_FN uint slice_runs(uint columns) { return (columns + uint(SLICE_RUN) - 1u) / uint(SLICE_RUN); }
KERNEL_FN uint slice_words(uint columns) { return slice_runs(columns) * uint(SLICE_RUN_WORDS); }

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

#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "slice_bindings.h"
#if SLICE_RUN_WORDS != 2
#error "a run's words are stored as one uvec2"
#endif

// The slice stage, with the post stage on each sample (slice_bindings.h): one invocation per
// SLICE_RUN pixels of a row. The grey volume is sampled trilinearly: through a linear sampler (the
// hardware's filter) at normalised coordinates (index + 0.5) / size, or from packed neighbours
// (SLICE_PACKED, their image tiled: slice_bindings.h); the labels share the volume's grid and are
// fetched at the nearest voxel.
layout(local_size_x = SLICE_GROUP_X, local_size_y = SLICE_GROUP_Y) in;
// The SliceParams flags this pipeline was made for (its dispatcher sets them from the frame's
// params): a constant, so the outputs and inputs switched off are compiled out, not masked.
layout(constant_id = 0) const uint FLAGS = 0u;
layout(binding = SLICE_VOLUME_BINDING) uniform sampler3D volume;
layout(binding = SLICE_LABELS_BINDING) uniform usampler3D labels;
layout(binding = SLICE_MAP_BINDING) uniform samplerBuffer map;
layout(std430, binding = SLICE_GREY_BINDING) writeonly buffer Grey { float grey_out[]; };
layout(std430, binding = SLICE_LABEL_OUT_BINDING) writeonly buffer LabelOut { uint label_out[]; };
layout(std430, binding = SLICE_DISPLAY_BINDING) writeonly buffer Display { uvec2 display[]; };
layout(std140, binding = SLICE_FRAME_BINDING) uniform Frame { SliceFrame frame; };
layout(binding = SLICE_ROWS_BINDING) uniform samplerBuffer post_rows;
layout(binding = SLICE_GENERATED_BINDING) uniform usamplerBuffer generated;

void main()
{
    uint run = gl_GlobalInvocationID.x, r = gl_GlobalInvocationID.y;
    SliceParams s = frame.slice;
    uint c0 = run * uint(SLICE_RUN);
    if (c0 >= s.columns || r >= s.rows) return;
    const bool warped = (FLAGS & SLICE_WARPED) != 0u, post = (FLAGS & SLICE_POST) != 0u;
    uvec3 voxels = uvec3(s.volume_x, s.volume_y, s.volume_z);
    vec3 size = vec3(voxels);
    ivec3 label_size = textureSize(labels, 0);
    vec4 row_texel = texelFetch(post_rows, int(r));
    PostRow row = PostRow(row_texel.x, row_texel.y, row_texel.z, row_texel.w);
    float y = pixel_y(r, s.pixel_y_mm);
    // the map columns the run reads (map_tap, slice_taps): fetched once for its pixels, a fetch
    // being the cost that counts on a CPU device, and picked per pixel by selects (a computed index
    // into an array would go through memory there)
    const uint TAPS = (FLAGS >> SLICE_TAPS_SHIFT) & 15u;
    uint first = 0u;
    vec2 taps[SLICE_RUN + 1];
    if (warped) {
        first = map_tap(c0, s).left;
        int row_start = int(r * s.map_columns), last = int(s.map_columns) - 1;
        [[unroll]] for (uint k = 0u; k < TAPS; ++k) taps[k] = texelFetch(map, row_start + min(int(first + k), last)).xy;
    }
    uvec2 packed = uvec2(0u);
    // a row's last run may reach past its last column: those bytes repeat that column (the copy
    // into the image leaves them), so every lane runs the same code
    [[unroll]] for (uint j = 0u; j < uint(SLICE_RUN); ++j) {
        uint c = min(c0 + j, s.columns - 1u);
        uint i = r * s.columns + c;
        vec2 m = vec2(y, 0.0);
        if (warped) {
            MapTap t = map_tap(c, s);
            vec2 left = taps[0], right = taps[0];
            [[unroll]] for (uint k = 1u; k < TAPS; ++k) {
                left = t.left == first + k ? taps[k] : left;
                right = t.right == first + k ? taps[k] : right;
            }
            m = map_between(left, right, t.right_weight);
        }
        vec3 index = vec3(s.probe_to_index * vec4(pixel_x(c, s.pixel_x_mm, s.width_mm), m.x, 0.0, 1.0));
        float grey = 0.0;
        if ((FLAGS & SLICE_GENERATED) != 0u) {
            // the live image already shows what the pressed tissue does to the sound below it
            grey = float(texelFetch(generated, int(r * ((s.columns + 3u) & ~3u) + c)).r);
            m.y = 0.0;
        } else if ((FLAGS & SLICE_PACKED) != 0u) {
            vec3 lo = clamp(floor(index), vec3(0.0), max(size - 2.0, vec3(0.0)));
            uvec3 at = uvec3(lo);
            uvec3 far_x = at + uvec3(min(1u, voxels.x - 1u), 0u, 0u);  // a volume one voxel wide has no far column
            float sample_ = packed_trilinear(texelFetch(volume, ivec3(packed_texel(at, s.fold_bits)), 0),
                                             texelFetch(volume, ivec3(packed_texel(far_x, s.fold_bits)), 0), index - lo);
            grey = inside_volume(index, size) ? sample_ * 255.0 : 0.0;
        } else {
            grey = inside_volume(index, size) ? texture(volume, (index + 0.5) / size).r * 255.0 : 0.0;
        }
        if ((FLAGS & SLICE_GREY) != 0u) grey_out[i] = grey;
        if ((FLAGS & SLICE_LABELS) != 0u) {
            ivec3 v = ivec3(floor(index + 0.5));
            bool in_map = all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, label_size));
            label_out[i] = in_map ? texelFetch(labels, v, 0).r : 0u;
        }
        uint shown = post ? post_pixel(c, grey, m.y, row, frame.post) : uint(grey + 0.5);
        packed[j / 4u] |= min(shown, 255u) << (8u * (j % 4u));
    }
    display[r * slice_runs(s.columns) + run] = packed;
}

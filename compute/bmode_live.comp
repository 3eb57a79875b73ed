#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"

// B-mode synthesis of a live frame, pass 1 (bmode_bindings.h; passes 2 to 4 are the sweep's): per
// pixel of the pressed image, where its tissue rests (the deform map's source depth at the pixel's
// lateral position, read between the map's columns as the slice stage reads it: map_tap,
// map_between), the tissue there (the case's labels, nearest voxel; where the map skips a closed
// vein's lumen, its last trace: bmode_coapted) and the scatterer field of the rest position. So the
// speckle stays attached to the tissue as it moves, and compresses as a real image's does: the
// scatterers come closer, the point-spread function does not shrink. The CPU
// twin is echo::synthesize_live (engine/echo/bmode.cpp), which calls the same functions.
layout(local_size_x = BMODE_SCATTER_GROUP_X, local_size_y = BMODE_SCATTER_GROUP_Y) in;
layout(std140, binding = BMODE_LIVE_FRAME_BINDING) uniform Live { BModeLiveFrame live; };
layout(binding = BMODE_LIVE_MAP_BINDING) uniform samplerBuffer map;
layout(binding = BMODE_VOLUME_BINDING) uniform usamplerBuffer tissue;
layout(std430, binding = BMODE_FIELD_BINDING) writeonly buffer Field { vec2 field[]; };
layout(std430, binding = BMODE_LABELS_BINDING) writeonly buffer Labels { uint labels[]; };

// the tissue code at (x, y) of the pressed probe's frame [mm] (nearest voxel; outside the labels: 0)
uint live_tissue(float x, float y, SliceParams s)
{
    const ivec3 v = ivec3(floor(vec3(s.probe_to_index * vec4(x, y, 0.0, 1.0)) + 0.5));
    const ivec3 size = ivec3(s.volume_x, s.volume_y, s.volume_z);
    const bool inside = all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, size));
    const ivec3 at_v = clamp(v, ivec3(0), size - 1);  // a CPU device fetches for every lane, inside or not
    const uint t = texelFetch(tissue, at_v.x + size.x * (at_v.y + size.y * at_v.z)).r;
    return inside && t < k.tissue_count ? t : 0u;
}

void main()
{
    const uint c = gl_GlobalInvocationID.x, r = gl_GlobalInvocationID.y;
    if (c >= k.columns || r >= k.rows) return;
    const SliceParams s = live.slice;
    float source_y = pixel_y(r, s.pixel_y_mm), above_y = source_y;
    if ((s.flags & SLICE_WARPED) != 0u) {
        const MapTap t = map_tap(c, s);
        const int row = int(r * s.map_columns);
        source_y = map_between(texelFetch(map, row + int(t.left)).xy, texelFetch(map, row + int(t.right)).xy, t.right_weight).x;
        const int row_above = int(max(r, 1u) - 1u) * int(s.map_columns);
        above_y = r > 0u ? map_between(texelFetch(map, row_above + int(t.left)).xy, texelFetch(map, row_above + int(t.right)).xy, t.right_weight).x
                         : source_y;
    }
    const float x = pixel_x(c, s.pixel_x_mm, s.width_mm);
    uint t = live_tissue(x, source_y, s);
    // (the tissue halfway across a skip looked up only where the map skips: a CPU device's lanes
    // then fetch it only where some lane of theirs needs it)
    if (source_y - above_y > BMODE_COAPTED_SKIP_MM) t = bmode_coapted(t, live_tissue(x, 0.5 * (source_y + above_y), s), source_y - above_y);
    const uint at = r * k.columns + c;
    field[at] = bmode_scattered(bmode_live_world(live.pose, x, source_y), vec3(live.pose.z), t, true);
    labels[at] = t;
}

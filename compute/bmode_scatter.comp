#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"

// B-mode synthesis, pass 1 (bmode_bindings.h): per pixel of each frame of the batch, the tissue at
// the pixel (nearest voxel of the label volume) and the complex scatterer field there, summed over
// the beam's elevational planes and scaled by the tissue's scattering. The CPU twin is
// echo::synthesize (engine/echo/bmode.cpp), which calls the same functions.
layout(local_size_x = BMODE_SCATTER_GROUP_X, local_size_y = BMODE_SCATTER_GROUP_Y) in;
layout(std140, binding = BMODE_FRAMES_BINDING) uniform Frames { BModeFrames poses; };
layout(binding = BMODE_VOLUME_BINDING) uniform usamplerBuffer volume;
layout(std430, binding = BMODE_FIELD_BINDING) writeonly buffer Field { vec2 field[]; };
layout(std430, binding = BMODE_LABELS_BINDING) writeonly buffer Labels { uint labels[]; };

void main()
{
    const uint c = gl_GlobalInvocationID.x, r = gl_GlobalInvocationID.y, f = gl_GlobalInvocationID.z;
    if (c >= k.columns || r >= k.rows) return;
    const BModePose pose = poses.frame[f];
    const vec3 p = bmode_pixel_world(pose, c, r, k.pixel_mm, k.width_mm);
    const int voxel = bmode_voxel(p);
    uint t = voxel < 0 ? 0u : texelFetch(volume, voxel).r;
    t = t < k.tissue_count ? t : 0u;  // the host checked the codes; a stray one reads as gel
    const uint at = (f * k.rows + r) * k.columns + c;
    field[at] = bmode_scattered(p, vec3(pose.z), t, false);
    labels[at] = t;
}

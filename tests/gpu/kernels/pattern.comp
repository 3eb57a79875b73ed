#version 450
#extension GL_GOOGLE_include_directive : require
#include "pattern_bindings.h"

// Writes texel (x, y) = ((7x + s) mod 256, (11y + 3s) mod 256, (xy + s) mod 256, 255) / 255.
layout(local_size_x = PATTERN_GROUP_X, local_size_y = PATTERN_GROUP_Y) in;
layout(binding = PATTERN_IMAGE_BINDING, rgba8) uniform writeonly image2D image;
layout(std140, binding = PATTERN_PARAMS_BINDING) uniform Params { PatternParams params; };

void main()
{
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= params.width || p.y >= params.height) return;
    uint s = params.seed;
    uvec4 texel = uvec4((7u * p.x + s) & 255u, (11u * p.y + 3u * s) & 255u, (p.x * p.y + s) & 255u, 255u);
    imageStore(image, ivec2(p), vec4(texel) / 255.0);
}

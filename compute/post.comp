#version 450
#extension GL_GOOGLE_include_directive : require
#include "post_bindings.h"

// The post stage: one invocation per pixel (the maths: post_grey in post_bindings.h, which the CPU
// twin runs too), written to the displayed image as opaque grey.
layout(local_size_x = POST_GROUP_X, local_size_y = POST_GROUP_Y) in;
layout(std430, binding = POST_GREY_BINDING) readonly buffer Grey { float grey[]; };
layout(std430, binding = POST_MAP_BINDING) readonly buffer Map { vec2 map[]; };
layout(binding = POST_IMAGE_BINDING, rgba8) uniform writeonly image2D image;
layout(push_constant) uniform Push { PostParams params; };

void main()
{
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= params.columns || px.y >= params.rows) return;
    uint i = px.y * params.columns + px.x;
    float gain = (params.flags & POST_WARPED) != 0u ? map[i].y : 0.0;
    float g = float(post_grey(px.x, px.y, grey[i], gain, params)) / 255.0;
    imageStore(image, ivec2(px), vec4(g, g, g, 1.0));
}

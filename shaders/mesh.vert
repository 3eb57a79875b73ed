#version 450
#extension GL_GOOGLE_include_directive : require
#include "mesh_bindings.h"

layout(set = MESH_FRAME_SET, binding = MESH_FRAME_BINDING) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_color;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_color;

void main()
{
    vec4 world = draw.model * vec4(in_position, 1.0);
    out_world = world.xyz;
    // models are rigid (rotation and translation), so the upper 3x3 also transforms normals
    out_normal = mat3(draw.model) * in_normal;
    out_color = in_color * draw.tint.rgb;
    gl_Position = frame.view_proj * world;
}

#version 450
#extension GL_GOOGLE_include_directive : require
#include "mesh_bindings.h"

layout(set = MESH_FRAME_SET, binding = MESH_FRAME_BINDING) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

#include "mesh_lighting.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_color;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_color;  // the albedo, or the lit colour as the target takes it unless LIT_PER_PIXEL

void main()
{
    vec4 world = draw.model * vec4(in_position, 1.0);
    // models are rigid (rotation and translation), so the upper 3x3 also transforms normals
    vec3 normal = mat3(draw.model) * in_normal;
    vec3 albedo = in_color * draw.tint.rgb;
    out_world = world.xyz;
    out_normal = normal;
    // the pipeline culls back faces, so the outward normal is the one lit
    out_color = LIT_PER_PIXEL ? albedo : for_target(shade(frame, normalize(normal), world.xyz, albedo, draw.tint.a));
    gl_Position = frame.view_proj * world;
}

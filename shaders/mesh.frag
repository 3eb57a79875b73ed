#version 450
#extension GL_GOOGLE_include_directive : require
#include "mesh_bindings.h"

layout(set = MESH_FRAME_SET, binding = MESH_FRAME_BINDING) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

#include "mesh_lighting.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_color;  // lit already unless LIT_PER_PIXEL

layout(location = 0) out vec4 out_color;

void main()
{
    if (!LIT_PER_PIXEL) {
        out_color = vec4(in_color, 1.0);
        return;
    }
    vec3 n = normalize(in_normal);
    if (!gl_FrontFacing) n = -n;
    float gloss = draw.tint.a;
    if (draw.material.x > 0.5) {
        vec4 g = frame.gel_from_world * vec4(in_world, 1.0);
        gloss *= 1.0 - smoothstep(0.55, 1.0, length(g.xz));
    }
    out_color = vec4(for_target(shade(frame, n, in_world, in_color, gloss)), draw.material.y > 0.0 ? draw.material.y : 1.0);
}

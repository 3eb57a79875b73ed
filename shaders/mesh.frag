#version 450
#extension GL_GOOGLE_include_directive : require
#include "mesh_bindings.h"

layout(set = MESH_FRAME_SET, binding = MESH_FRAME_BINDING) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_color;

layout(location = 0) out vec4 out_color;

// Skin-like shading: wrapped diffuse (light bleeding past the terminator, as in skin), hemisphere
// ambient, a soft specular lobe whose strength follows the draw's glossiness, and a faint rim.
// Output is linear; the sRGB attachment encodes it.
void main()
{
    vec3 n = normalize(in_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 v = normalize(frame.eye.xyz - in_world);
    const vec3 up = vec3(0.0, -1.0, 0.0);  // anterior: the patient lies supine

    const float wrap = 0.35;
    vec3 l_key = -frame.key_dir.xyz;
    vec3 l_fill = -frame.fill_dir.xyz;
    float key = max((dot(n, l_key) + wrap) / (1.0 + wrap), 0.0) * frame.key_dir.w;
    float fill = max((dot(n, l_fill) + wrap) / (1.0 + wrap), 0.0) * frame.fill_dir.w;
    vec3 ambient = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * dot(n, up));

    float gloss = draw.tint.a;
    vec3 h = normalize(l_key + v);
    float spec = pow(max(dot(n, h), 0.0), mix(12.0, 90.0, gloss)) * mix(0.06, 0.55, gloss) * frame.key_dir.w;
    float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0) * 0.12;

    vec3 color = in_color * (ambient + vec3(1.0, 0.97, 0.92) * key + vec3(0.75, 0.82, 1.0) * fill) + vec3(spec + rim);
    out_color = vec4(color, 1.0);
}

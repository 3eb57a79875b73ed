// The scene's lighting, one function for both places it is evaluated: per vertex for the dense,
// matte meshes (the legs, the drape, the table: their vertices lie millimetres apart, so the
// interpolated colour cannot be told from per-pixel shading, at a tenth of the cost on a CPU
// rasteriser) and per pixel for the glossy ones (the gel on the patch, the probe's plastic), whose
// highlights are smaller than their triangles. Included by mesh.vert and mesh.frag after
// mesh_bindings.h.
#ifndef ECHOSIM_MESH_LIGHTING_GLSL
#define ECHOSIM_MESH_LIGHTING_GLSL

#include "srgb.glsl"

// Whether the fragment shader lights (else the vertex shader does): specialization constant 0 of
// both stages, set per pipeline by the scene pass.
layout(constant_id = 0) const bool LIT_PER_PIXEL = true;
// Whether the target's format is sRGB, so it encodes the linear colours written (constant 1, from
// the target's format). Where it is not (echosim's own targets: gpu/window.cpp), the shader encodes:
// per vertex for the vertex-lit meshes, a colour interpolated between display values that differs
// from the linear interpolation by less than a level over their millimetre triangles, at a fraction
// of the cost of an encode per pixel on a CPU rasteriser.
layout(constant_id = 1) const bool TARGET_ENCODES = true;

// A linear colour as the target must be written.
vec3 for_target(vec3 linear) { return TARGET_ENCODES ? linear : linear_to_srgb(linear); }

// Skin-like shading: wrapped diffuse (light bleeding past the terminator, as in skin), hemisphere
// ambient, a soft specular lobe whose strength follows the draw's glossiness, and a faint rim.
// `n` is the unit normal at `world` [mm]; the result is linear (for_target writes it).
vec3 shade(FrameUniforms frame, vec3 n, vec3 world, vec3 albedo, float gloss)
{
    vec3 v = normalize(frame.eye.xyz - world);
    const vec3 up = vec3(0.0, -1.0, 0.0);  // anterior: the patient lies supine

    const float wrap = 0.35;
    vec3 l_key = -frame.key_dir.xyz;
    vec3 l_fill = -frame.fill_dir.xyz;
    float key = max((dot(n, l_key) + wrap) / (1.0 + wrap), 0.0) * frame.key_dir.w;
    float fill = max((dot(n, l_fill) + wrap) / (1.0 + wrap), 0.0) * frame.fill_dir.w;
    vec3 ambient = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * dot(n, up));

    vec3 h = normalize(l_key + v);
    float spec = pow(max(dot(n, h), 0.0), mix(12.0, 90.0, gloss)) * mix(0.06, 0.55, gloss) * frame.key_dir.w;
    float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0) * 0.12;

    return albedo * (ambient + vec3(1.0, 0.97, 0.92) * key + vec3(0.75, 0.82, 1.0) * fill) + vec3(spec + rim);
}

#endif

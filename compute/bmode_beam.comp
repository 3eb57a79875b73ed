#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"

// B-mode synthesis, pass 2 (bmode_bindings.h): per column of each frame, down the beam: attenuation
// less TGC, specular echoes where the tissue changes and the shadow of what they reflect
// (bmode_beam_step), from buffer A into buffer B.
layout(local_size_x = BMODE_BEAM_GROUP) in;
layout(binding = BMODE_FIELD_TEXELS_BINDING) uniform samplerBuffer field;
layout(binding = BMODE_LABEL_TEXELS_BINDING) uniform usamplerBuffer labels;
layout(std430, binding = BMODE_BEAM_BINDING) writeonly buffer Beam { vec2 beam[]; };

void main()
{
    const uint c = gl_GlobalInvocationID.x, f = gl_GlobalInvocationID.y;
    if (c >= k.columns) return;
    const uint base = f * k.rows * k.columns + c;
    float transmitted = 1.0;
    uint above = 0u;
    for (uint r = 0u; r < k.rows; ++r) {
        const int at = int(base + r * k.columns);
        const uint t = texelFetch(labels, at).r;
        beam[at] = bmode_beam_step(texelFetch(field, at).xy, above, t, r == 0u, transmitted);
        above = t;
    }
}

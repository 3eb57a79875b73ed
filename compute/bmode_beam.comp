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
    // runs of BEAM_RUN rows, their loads issued together before the run's steps: only `transmitted`
    // carries from row to row, and a GPU's column thread (a thousand of them at most) would
    // otherwise wait out a load's latency at every row (the steps and their order are the twin's)
    const uint BEAM_RUN = 16u;
    for (uint r0 = 0u; r0 < k.rows; r0 += BEAM_RUN) {
        uint t[BEAM_RUN];
        vec2 f[BEAM_RUN];
        for (uint i = 0u; i < BEAM_RUN; ++i) {
            const int at = int(base + min(r0 + i, k.rows - 1u) * k.columns);
            t[i] = texelFetch(labels, at).r;
            f[i] = texelFetch(field, at).xy;
        }
        for (uint i = 0u; i < BEAM_RUN && r0 + i < k.rows; ++i) {
            beam[int(base + (r0 + i) * k.columns)] = bmode_beam_step(f[i], above, t[i], r0 + i == 0u, transmitted);
            above = t[i];
        }
    }
}

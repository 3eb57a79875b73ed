#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"

// B-mode synthesis, pass 2 (bmode_bindings.h): per column of each frame, down the beam: attenuation
// less TGC, specular echoes where the tissue changes and the shadow of what they reflect
// (bmode_beam_step); then the axial point-spread function down the same column. One invocation owns
// its column, so it reads back what it wrote without a barrier.
layout(local_size_x = BMODE_BEAM_GROUP) in;
layout(std430, binding = BMODE_FIELD_BINDING) buffer Field { vec2 field[]; };
layout(std430, binding = BMODE_LABELS_BINDING) readonly buffer Labels { uint labels[]; };
layout(std430, binding = BMODE_AXIAL_BINDING) writeonly buffer Axial { vec2 axial[]; };

void main()
{
    const uint c = gl_GlobalInvocationID.x, f = gl_GlobalInvocationID.y;
    if (c >= k.columns) return;
    const uint base = f * k.rows * k.columns + c;
    float transmitted = 1.0;
    uint above = 0u;
    for (uint r = 0u; r < k.rows; ++r) {
        const uint at = base + r * k.columns;
        const uint t = labels[at];
        field[at] = bmode_beam_step(field[at], above, t, r == 0u, transmitted);
        above = t;
    }
    const int ra = int(k.axial_radius), rows = int(k.rows);
    for (int r = 0; r < rows; ++r) {
        precise vec2 s = vec2(0.0);
        for (int d = -ra; d <= ra; ++d) {
            const int rr = r + d;
            if (rr >= 0 && rr < rows) {
                precise vec2 term = field[base + uint(rr) * k.columns] * bmode_axial_tap(uint(d + ra));
                s = s + term;
            }
        }
        axial[base + uint(r) * k.columns] = s;
    }
}

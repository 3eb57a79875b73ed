#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"

// B-mode synthesis, pass 3 (bmode_bindings.h): per run of 4 rows of a column of each frame, the
// axial point-spread function down the column, from buffer B into buffer A.
layout(local_size_x = BMODE_AXIAL_GROUP_X, local_size_y = BMODE_AXIAL_GROUP_Y) in;
layout(binding = BMODE_BEAM_TEXELS_BINDING) uniform samplerBuffer beam;
layout(std430, binding = BMODE_FIELD_BINDING) writeonly buffer Field { vec2 field[]; };

void main()
{
    // a run of 4 rows of a column: each texel fetched once, a term joining sum q where it lies
    // within the PSF of row r0 + q, each sum taking its terms in the CPU twin's order
    const uint c = gl_GlobalInvocationID.x, run = gl_GlobalInvocationID.y, f = gl_GlobalInvocationID.z;
    const int r0 = int(run * 4u), rows = int(k.rows), columns = int(k.columns);
    if (c >= k.columns || r0 >= rows) return;
    const int ra = int(k.axial_radius), base = int(f * k.rows * k.columns + c);
    precise vec2 s0 = vec2(0.0), s1 = vec2(0.0), s2 = vec2(0.0), s3 = vec2(0.0);
    for (int e = max(r0 - ra, 0); e <= min(r0 + 3 + ra, rows - 1); ++e) {
        const vec2 a = texelFetch(beam, base + e * columns).xy;
        const int d = e - r0 + ra;
        if (d <= 2 * ra) { precise vec2 t0 = a * bmode_axial_tap(uint(d)); s0 = s0 + t0; }
        if (d >= 1 && d - 1 <= 2 * ra) { precise vec2 t1 = a * bmode_axial_tap(uint(d - 1)); s1 = s1 + t1; }
        if (d >= 2 && d - 2 <= 2 * ra) { precise vec2 t2 = a * bmode_axial_tap(uint(d - 2)); s2 = s2 + t2; }
        if (d >= 3) { precise vec2 t3 = a * bmode_axial_tap(uint(d - 3)); s3 = s3 + t3; }
    }
    field[base + r0 * columns] = s0;
    if (r0 + 1 < rows) field[base + (r0 + 1) * columns] = s1;
    if (r0 + 2 < rows) field[base + (r0 + 2) * columns] = s2;
    if (r0 + 3 < rows) field[base + (r0 + 3) * columns] = s3;
}

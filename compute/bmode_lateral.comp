#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"
#include "log_compress_bindings.h"

// B-mode synthesis, pass 4 (bmode_bindings.h): per run of 4 pixels of a row of each frame, the
// lateral point-spread function across the row, the envelope, and log compression (the expression
// of log_compress.comp); the grey levels and the tissue codes packed 4 to a word. Variant
// BMODE_WITH_ENVELOPE also writes the envelope (the tests' speckle statistics).
layout(local_size_x = BMODE_LATERAL_GROUP_X, local_size_y = BMODE_LATERAL_GROUP_Y) in;
layout(constant_id = 0) const uint variant = 0u;
layout(binding = BMODE_LABEL_TEXELS_BINDING) uniform usamplerBuffer labels;
layout(binding = BMODE_FIELD_TEXELS_BINDING) uniform samplerBuffer axial;  // buffer A, after the axial PSF
layout(std430, binding = BMODE_GREY_BINDING) writeonly buffer Grey { uint grey[]; };
layout(std430, binding = BMODE_LABEL_OUT_BINDING) writeonly buffer LabelOut { uint label_out[]; };
layout(std430, binding = BMODE_ENVELOPE_BINDING) writeonly buffer Envelope { float envelope[]; };

void main()
{
    const uint w = gl_GlobalInvocationID.x, r = gl_GlobalInvocationID.y, f = gl_GlobalInvocationID.z;
    if (w >= k.row_words || r >= k.rows) return;
    const uint row = (f * k.rows + r) * k.columns;
    const int rl = int(k.lateral_radius), columns = int(k.columns);
    // the run's 4 sums at once, each texel fetched once: a term joins sum q where it lies within
    // the PSF of pixel c0 + q; each sum takes its terms in the order the CPU twin adds them
    const int c0 = int(w * 4u);
    precise vec2 s0 = vec2(0.0), s1 = vec2(0.0), s2 = vec2(0.0), s3 = vec2(0.0);
    for (int e = max(c0 - rl, 0); e <= min(c0 + 3 + rl, columns - 1); ++e) {
        const vec2 a = texelFetch(axial, int(row) + e).xy;
        const int d = e - c0 + rl;  // tap of pixel c0 (then d - 1 of c0 + 1, ...)
        if (d <= 2 * rl) { precise vec2 t0 = a * bmode_lateral_tap(uint(d)); s0 = s0 + t0; }
        if (d >= 1 && d - 1 <= 2 * rl) { precise vec2 t1 = a * bmode_lateral_tap(uint(d - 1)); s1 = s1 + t1; }
        if (d >= 2 && d - 2 <= 2 * rl) { precise vec2 t2 = a * bmode_lateral_tap(uint(d - 2)); s2 = s2 + t2; }
        if (d >= 3) { precise vec2 t3 = a * bmode_lateral_tap(uint(d - 3)); s3 = s3 + t3; }
    }
    uint grey_word = 0u, label_word = 0u;
    for (uint q = 0u; q < 4u; ++q) {
        const uint c = w * 4u + q;
        if (c >= k.columns) break;
        const vec2 s = q == 0u ? s0 : q == 1u ? s1 : q == 2u ? s2 : s3;
        const float e = bmode_envelope(s);
        if ((variant & BMODE_WITH_ENVELOPE) != 0u) envelope[row + c] = e;
        const float db = 20.0 * log2(max(e, 1e-20) / k.reference) * 0.30102999566 + k.gain_db;  // log10(x) = log2(x) log10(2)
        grey_word |= display_grey(db, k.dynamic_range_db) << (8u * q);
        label_word |= texelFetch(labels, int(row + c)).r << (8u * q);
    }
    const uint out_at = (f * k.rows + r) * k.row_words + w;
    grey[out_at] = grey_word;
    label_out[out_at] = label_word;
}

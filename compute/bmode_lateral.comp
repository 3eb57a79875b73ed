#version 450
#extension GL_GOOGLE_include_directive : require
#include "bmode_bindings.h"
#include "log_compress_bindings.h"

// B-mode synthesis, pass 3 (bmode_bindings.h): per run of 4 pixels of a row of each frame, the
// lateral point-spread function across the row, the envelope, and log compression (the expression
// of log_compress.comp); the grey levels and the tissue codes packed 4 to a word. Variant
// BMODE_WITH_ENVELOPE also writes the envelope (the tests' speckle statistics).
layout(local_size_x = BMODE_LATERAL_GROUP_X, local_size_y = BMODE_LATERAL_GROUP_Y) in;
layout(constant_id = 0) const uint variant = 0u;
layout(std430, binding = BMODE_LABELS_BINDING) readonly buffer Labels { uint labels[]; };
layout(binding = BMODE_AXIAL_TEXELS_BINDING) uniform samplerBuffer axial;
layout(std430, binding = BMODE_GREY_BINDING) writeonly buffer Grey { uint grey[]; };
layout(std430, binding = BMODE_LABEL_OUT_BINDING) writeonly buffer LabelOut { uint label_out[]; };
layout(std430, binding = BMODE_ENVELOPE_BINDING) writeonly buffer Envelope { float envelope[]; };

void main()
{
    const uint w = gl_GlobalInvocationID.x, r = gl_GlobalInvocationID.y, f = gl_GlobalInvocationID.z;
    if (w >= k.row_words || r >= k.rows) return;
    const uint row = (f * k.rows + r) * k.columns;
    const int rl = int(k.lateral_radius), columns = int(k.columns);
    uint grey_word = 0u, label_word = 0u;
    for (uint q = 0u; q < 4u; ++q) {
        const uint c = w * 4u + q;
        if (c >= k.columns) break;
        precise vec2 s = vec2(0.0);
        for (int d = -rl; d <= rl; ++d) {
            const int cc = int(c) + d;
            if (cc >= 0 && cc < columns) {
                precise vec2 term = texelFetch(axial, int(row) + cc).xy * bmode_lateral_tap(uint(d + rl));
                s = s + term;
            }
        }
        const float e = bmode_envelope(s);
        if ((variant & BMODE_WITH_ENVELOPE) != 0u) envelope[row + c] = e;
        const float db = 20.0 * log2(max(e, 1e-20) / k.reference) * 0.30102999566 + k.gain_db;  // log10(x) = log2(x) log10(2)
        grey_word |= display_grey(db, k.dynamic_range_db) << (8u * q);
        label_word |= labels[row + c] << (8u * q);
    }
    const uint out_at = (f * k.rows + r) * k.row_words + w;
    grey[out_at] = grey_word;
    label_out[out_at] = label_word;
}

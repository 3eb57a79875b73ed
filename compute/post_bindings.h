// The maths of the post stage of the echographic image, as on a scanner: the sliced grey level back
// to echo strength in dB (the volume's own log compression undone over its dynamic range), then
// gain, time-gain compensation (eight sliders down the depth, as on a console), the deform stage's
// gain (the posterior enhancement a closed lumen takes away), and the display's log compression
// (log_compress_bindings.h) over the chosen dynamic range; depth ticks every 5 mm on the left
// (longer every 10 mm) and the focus marker on the right. The slice kernel (compute/slice.comp)
// runs it on each sample it takes (slice_bindings.h says why there is no separate dispatch); its CPU
// twin is engine/echo/post_cpu.cpp.
#ifndef ECHOSIM_POST_BINDINGS_H
#define ECHOSIM_POST_BINDINGS_H

#include "deform_bindings.h"
#include "log_compress_bindings.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

#define POST_WARPED 1u   // add the deform map's gain
#define POST_MARKERS 2u  // draw the depth ticks and the focus marker

struct PostParams {
    uint columns;
    uint rows;
    float pixel_x_mm;
    float pixel_y_mm;
    float depth_mm;
    float volume_dynamic_range_db;  // the dB the volume's 0..255 spans (its B-mode synthesis' dynamic range)
    float gain_db;
    float dynamic_range_db;         // the display's
    float focus_mm;                 // the transmit focus' depth [mm]
    uint flags;                     // POST_WARPED | POST_MARKERS
    uint pad0;
    uint pad1;
    vec4 tgc_near;  // [dB] at depths (i + 0.5) / 8 of the image, i = 0..3
    vec4 tgc_far;   // i = 4..7
};

// The time-gain compensation at depth y [mm]: the sliders' values joined linearly, flat beyond.
// Written as hat weights over the eight sliders rather than by indexing a vector with a computed
// index, which llvmpipe turns into a per-lane loop through memory (it cost 4 ms a 1024² frame).
KERNEL_FN float tgc_db(float y, PostParams p)
{
    float at = clamp(y / p.depth_mm * 8.0f - 0.5f, 0.0f, 7.0f);
    vec4 near_w = max(vec4(0.0f), vec4(1.0f) - abs(vec4(at) - vec4(0.0f, 1.0f, 2.0f, 3.0f)));
    vec4 far_w = max(vec4(0.0f), vec4(1.0f) - abs(vec4(at) - vec4(4.0f, 5.0f, 6.0f, 7.0f)));
    return dot(p.tgc_near, near_w) + dot(p.tgc_far, far_w);
}

// What a row of the image shares: the display level (0..1) a sliced grey of 0 takes on it before
// the deform stage's gain (the volume's dB, the gain, the TGC and the display's dynamic range in one
// offset), how many columns from the left its depth tick covers (0: none), and the column past
// which the focus' triangle covers it (columns - 1 or more: not on this row). The per-pixel part
// (post_pixel) is then two compares and two multiply-adds; the slice kernel reads the rows' from a
// table its dispatcher fills (computed in the kernel, once per four pixels, this cost llvmpipe half
// the frame).
struct PostRow {
    float level_offset;
    float tick_columns;
    float focus_column;
    float pad;  // a row is one RGBA32F texel of the slice kernel's table
};

KERNEL_FN PostRow post_row(uint r, PostParams p)
{
    float y = pixel_y(r, p.pixel_y_mm);
    PostRow row;
    // level = (db + range) / range, db = (grey / 255 - 1) vdr + gain + tgc (+ the deform's gain)
    row.level_offset = (p.gain_db + tgc_db(y, p) - p.volume_dynamic_range_db + p.dynamic_range_db) / p.dynamic_range_db;
    row.tick_columns = 0.0f;
    row.focus_column = float(p.columns);
    row.pad = 0.0f;
    if ((p.flags & POST_MARKERS) == 0u) return row;
    float thick = max(p.pixel_y_mm, p.depth_mm / 300.0f);  // [mm] a tick's height
    float tick = floor(y / 5.0f + 0.5f) * 5.0f;
    if (tick > 0.0f && tick < p.depth_mm && abs(y - tick) < 0.5f * thick) {
        bool major = mod(tick, 10.0f) < 0.5f;
        row.tick_columns = float(p.columns) * (major ? 0.03f : 0.015f) + 1.0f;
    }
    // the triangle: half height `size` [mm] at the right edge, narrowing to a point 2 size in
    float size = p.depth_mm / 80.0f;
    float reach_mm = 2.0f * (size - abs(y - p.focus_mm));
    if (reach_mm > 0.0f) row.focus_column = float(p.columns - 1u) - reach_mm / p.pixel_x_mm;
    return row;
}

// The displayed grey of pixel column c on `row`, whose sliced grey level is `grey` and whose
// deform gain is `gain_db`.
KERNEL_FN uint post_pixel(uint c, float grey, float gain_db, PostRow row, PostParams p)
{
    float column = float(c);
    if (column < row.tick_columns || column > row.focus_column) return 255u;
    float level = grey * (p.volume_dynamic_range_db / (255.0f * p.dynamic_range_db)) + row.level_offset;
    if ((p.flags & POST_WARPED) != 0u) level += gain_db / p.dynamic_range_db;
    return grey_of_level(level);
}

// The displayed grey of pixel (c, r): post_pixel on post_row(r).
KERNEL_FN uint post_grey(uint c, uint r, float grey, float gain_db, PostParams p)
{
    return post_pixel(c, grey, gain_db, post_row(r, p), p);
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif

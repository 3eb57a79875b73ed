// Bindings of compute/post.comp, the post stage of the echographic image, as on a scanner: the
// sliced grey level back to echo strength in dB (the volume's own log compression undone over its
// dynamic range), then gain, time-gain compensation (eight sliders down the depth, as on a
// console), the deform stage's gain (the posterior enhancement a closed lumen takes away), and the
// display's log compression (log_compress_bindings.h) over the chosen dynamic range; depth ticks
// every 5 mm on the left (longer every 10 mm) and the focus marker on the right. Shared with its CPU
// twin (engine/echo/post_cpu.cpp) and its dispatcher (engine/image/echo_image_gpu.cpp).
#ifndef ECHOSIM_POST_BINDINGS_H
#define ECHOSIM_POST_BINDINGS_H

#include "deform_bindings.h"
#include "log_compress_bindings.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

#define POST_GROUP_X 16
#define POST_GROUP_Y 8
#define POST_GREY_BINDING 0   // float per pixel from the slice stage: grey 0..255
#define POST_MAP_BINDING 1    // vec2 per pixel from the deform stage (its gain read when POST_WARPED)
#define POST_IMAGE_BINDING 2  // rgba8 storage image: the displayed image

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
KERNEL_FN float tgc_db(float y, PostParams p)
{
    float at = clamp(y / p.depth_mm * 8.0f - 0.5f, 0.0f, 7.0f);
    uint i = min(uint(at), 6u);
    float f = at - float(i);
    vec4 lo = i < 4u ? p.tgc_near : p.tgc_far, hi = i + 1u < 4u ? p.tgc_near : p.tgc_far;
    return mix(lo[i % 4u], hi[(i + 1u) % 4u], f);
}

// Whether pixel (c, r) shows a marker: a depth tick or the focus' triangle.
KERNEL_FN bool marker_at(uint c, uint r, PostParams p)
{
    float y = pixel_y(r, p.pixel_y_mm);
    float thick = max(p.pixel_y_mm, p.depth_mm / 300.0f);  // [mm] a tick's height
    float tick = floor(y / 5.0f + 0.5f) * 5.0f;
    if (tick > 0.0f && tick < p.depth_mm && abs(y - tick) < 0.5f * thick) {
        bool major = mod(tick, 10.0f) < 0.5f;
        float length = float(p.columns) * (major ? 0.03f : 0.015f) + 1.0f;
        if (float(c) < length) return true;
    }
    float from_right = float(p.columns - 1u - c) * p.pixel_x_mm;  // [mm]
    float size = p.depth_mm / 80.0f;                                // the triangle's half height [mm]
    return from_right < 2.0f * size && abs(y - p.focus_mm) < size * (1.0f - from_right / (2.0f * size));
}

// The displayed grey of a pixel whose sliced grey level is `grey` and whose deform gain is `gain_db`.
KERNEL_FN uint post_grey(uint c, uint r, float grey, float gain_db, PostParams p)
{
    if ((p.flags & POST_MARKERS) != 0u && marker_at(c, r, p)) return 255u;
    float db = (grey / 255.0f - 1.0f) * p.volume_dynamic_range_db + p.gain_db + tgc_db(pixel_y(r, p.pixel_y_mm), p) +
               ((p.flags & POST_WARPED) != 0u ? gain_db : 0.0f);
    return display_grey(db, p.dynamic_range_db);
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif

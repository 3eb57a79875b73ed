// Small raster operations on RgbaImage for the pictures the project draws itself (reports, sheets
// of thumbnails): a filled rectangle, an image shrunk into a rectangle, text cut to a width.
#pragma once

#include <string>

#include "io/bitmap_font.hpp"
#include "io/png.hpp"

namespace echosim::io {

// The rectangle (x0, y0) w x h composited with `colour` (source over); what lies off the image is skipped.
void fill_rect(RgbaImage& img, int x0, int y0, int w, int h, Rgba colour);

// `src` into `dst` at (x0, y0), shrunk by a box filter to w x h (a stretched one is sampled
// nearest), composited source over; what lies off `dst` is skipped.
void blit_scaled(RgbaImage& dst, const RgbaImage& src, int x0, int y0, int w, int h);

// `text` cut to `width` pixels of the bitmap font at `scale`, with "..." when cut.
std::string fit_text(const std::string& text, int width, int scale);

}  // namespace echosim::io

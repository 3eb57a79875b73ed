// A hand-drawn 5x7 bitmap font for printable ASCII, so report figures can carry text without a font
// library. Glyphs sit in a 5x8 cell: seven rows above the baseline and one below for descenders.
#pragma once

#include <cstdint>
#include <string_view>

#include "io/png.hpp"

namespace echosim::io {

struct Rgba {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;
    std::uint8_t a = 255;
};

// Source-over compositing of `colour` scaled by `coverage` (0..1). Pixels outside the image are
// ignored, so callers may draw shapes that run off the canvas without clipping them first.
void blend_pixel(RgbaImage& image, int x, int y, Rgba colour, float coverage = 1.0f);

inline constexpr int glyph_width = 5;
inline constexpr int glyph_height = 8;   // cap height 7 plus the descender row
inline constexpr int glyph_spacing = 1;  // blank columns between neighbouring glyphs

enum class TextDirection {
    horizontal,
    up,  // rotated 90 degrees counter-clockwise, reading bottom to top (a y-axis label)
};

// Length of `text` along its reading direction, in pixels. Each UTF-8 character counts as one glyph
// (characters outside ASCII 32..126 are drawn as '?'), so a label with a stray "°" keeps its layout.
int text_width(std::string_view text, int scale = 1);
inline int text_height(int scale = 1) { return glyph_height * scale; }

// (x, y) is the top-left corner of the text's bounding box in the image, whatever the direction:
// text_width x text_height when horizontal, text_height x text_width when up. scale < 1 counts as 1.
void draw_text(RgbaImage& image, int x, int y, std::string_view text, int scale, Rgba colour,
               TextDirection direction = TextDirection::horizontal);

}  // namespace echosim::io

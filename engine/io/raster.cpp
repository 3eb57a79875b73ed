#include "io/raster.hpp"

#include <algorithm>
#include <cstdint>

namespace echosim::io {

void fill_rect(RgbaImage& img, int x0, int y0, int w, int h, Rgba colour)
{
    for (int y = std::max(0, y0); y < std::min<int>(int(img.height), y0 + h); ++y)
        for (int x = std::max(0, x0); x < std::min<int>(int(img.width), x0 + w); ++x) blend_pixel(img, x, y, colour);
}

void blit_scaled(RgbaImage& dst, const RgbaImage& src, int x0, int y0, int w, int h)
{
    if (src.width == 0 || src.height == 0 || w <= 0 || h <= 0) return;
    for (int y = 0; y < h; ++y) {
        const std::uint32_t sy0 = std::uint32_t(std::uint64_t(y) * src.height / std::uint32_t(h));
        const std::uint32_t sy1 = std::max(sy0 + 1, std::uint32_t(std::uint64_t(y + 1) * src.height / std::uint32_t(h)));
        for (int x = 0; x < w; ++x) {
            const std::uint32_t sx0 = std::uint32_t(std::uint64_t(x) * src.width / std::uint32_t(w));
            const std::uint32_t sx1 = std::max(sx0 + 1, std::uint32_t(std::uint64_t(x + 1) * src.width / std::uint32_t(w)));
            double sum[4] = {0, 0, 0, 0};
            for (std::uint32_t sy = sy0; sy < sy1; ++sy)
                for (std::uint32_t sx = sx0; sx < sx1; ++sx)
                    for (int k = 0; k < 4; ++k) sum[k] += src.at(sx, sy)[k];
            const double n = double((sy1 - sy0) * (sx1 - sx0));
            const Rgba c{std::uint8_t(sum[0] / n + 0.5), std::uint8_t(sum[1] / n + 0.5), std::uint8_t(sum[2] / n + 0.5),
                         std::uint8_t(sum[3] / n + 0.5)};
            blend_pixel(dst, x0 + x, y0 + y, c);
        }
    }
}

std::string fit_text(const std::string& text, int width, int scale)
{
    if (text_width(text, scale) <= width) return text;
    std::string cut = text;
    while (!cut.empty() && text_width(cut + "...", scale) > width) cut.pop_back();
    return cut + "...";
}

}  // namespace echosim::io

// Comparison of a rendered image with a reference under a written tolerance (Filament's renderdiff
// habit): a pixel fails when any channel differs by more than `max_channel_diff`; the image fails
// when more than `max_failed_fraction` of its pixels fail.
#pragma once

#include <cstdlib>
#include <string>

#include "io/png.hpp"

namespace echosim::test {

struct Tolerance {
    int max_channel_diff;
    double max_failed_fraction;
};

struct Comparison {
    bool same_size = false;
    double failed_fraction = 1.0;
    int worst_channel_diff = 255;
    std::string describe() const
    {
        return "failed pixels " + std::to_string(failed_fraction * 100.0) + " %, worst channel difference " +
               std::to_string(worst_channel_diff);
    }
};

inline Comparison compare(const io::RgbaImage& a, const io::RgbaImage& b, int max_channel_diff)
{
    Comparison c;
    c.same_size = a.width == b.width && a.height == b.height;
    if (!c.same_size) return c;
    std::size_t failed = 0;
    c.worst_channel_diff = 0;
    for (std::size_t p = 0; p < a.pixels.size(); p += 4) {
        int worst = 0;
        for (int ch = 0; ch < 4; ++ch) worst = std::max(worst, std::abs(int(a.pixels[p + ch]) - int(b.pixels[p + ch])));
        c.worst_channel_diff = std::max(c.worst_channel_diff, worst);
        failed += worst > max_channel_diff;
    }
    c.failed_fraction = double(failed) / double(a.pixels.size() / 4);
    return c;
}

inline bool within(const Comparison& c, const Tolerance& t)
{
    return c.same_size && c.failed_fraction <= t.max_failed_fraction;
}

}  // namespace echosim::test

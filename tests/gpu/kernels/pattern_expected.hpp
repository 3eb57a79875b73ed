// The texels pattern.comp writes, computed here in C++ on their own, for the tests to compare with.
#pragma once

#include <array>
#include <cstdint>

namespace echosim::test {

inline std::array<std::uint8_t, 4> pattern_texel(std::uint32_t x, std::uint32_t y, std::uint32_t seed)
{
    return {std::uint8_t((7 * x + seed) % 256), std::uint8_t((11 * y + 3 * seed) % 256), std::uint8_t((x * y + seed) % 256), 255};
}

}  // namespace echosim::test

// The largest image any command makes, rendered frame or echographic image: at most 8192 pixels a
// side and 7680 x 4320 (8K UHD) in all. Past that a frame's buffers (colour, depth, read-back,
// PNG rows: about 20 bytes a pixel, 660 MB at the limit) outgrow a kiosk's memory, and a request
// for 16384 x 16384 took 4.4 GB and 20 s before it was refused.
#pragma once

#include <cstdint>

namespace echosim {

inline constexpr std::uint32_t kMaxImageSide = 8192;
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(7680) * 4320;

}  // namespace echosim

// PNG files of 8-bit RGBA images, written through a temporary file and renamed, so an interrupted
// write never leaves a truncated PNG that looks valid.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace echosim::io {

struct RgbaImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> pixels;  // row-major, top row first, 4 bytes a pixel

    std::uint8_t* at(std::uint32_t x, std::uint32_t y) { return &pixels[(std::size_t(y) * width + x) * 4]; }
    const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
};

// Throws std::runtime_error naming the file on any failure.
void write_png(const std::filesystem::path& path, const RgbaImage& image);
RgbaImage read_png(const std::filesystem::path& path);

}  // namespace echosim::io

// The CPU reference of log compression (engine/echo) against the decibel scale it implements; the
// GPU kernel is compared with it in tests/image/log_compress_gpu_test.cpp.
#include "echo/log_compress.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace echosim::echo {
namespace {

std::uint32_t grey(std::uint32_t rgba) { return rgba & 0xffu; }

TEST(LogCompress, CpuReferenceMatchesTheDecibelScale)
{
    const LogCompressParams p{0, 100.0f, 0.0f, 60.0f};
    EXPECT_EQ(grey(log_compress_pixel(100.0f, p)), 255u);  // 0 dB: white
    EXPECT_EQ(grey(log_compress_pixel(1000.0f, p)), 255u); // above: clipped
    EXPECT_EQ(grey(log_compress_pixel(0.1f, p)), 0u);      // -60 dB: black
    EXPECT_EQ(grey(log_compress_pixel(0.0f, p)), 0u);
    EXPECT_EQ(grey(log_compress_pixel(100.0f * std::pow(10.0f, -30.0f / 20.0f), p)), 128u);  // half the range
    // +6 dB of gain lifts -6 dB to white
    const LogCompressParams gained{0, 100.0f, 6.0f, 60.0f};
    EXPECT_EQ(grey(log_compress_pixel(100.0f * std::pow(10.0f, -6.0f / 20.0f), gained)), 255u);
    EXPECT_EQ(log_compress_pixel(100.0f, p) >> 24, 255u);  // opaque
}

}  // namespace
}  // namespace echosim::echo

#include "io/png.hpp"

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "io/partial_left.hpp"
#include "test_files.hpp"

namespace echosim::io {
namespace {

std::filesystem::path temp(const char* name)
{
    return std::filesystem::temp_directory_path() / (std::string("echosim_png_test_") + std::to_string(::getpid()) + name);
}

TEST(Png, RoundTripsEveryByte)
{
    RgbaImage img{7, 5, {}};
    img.pixels.resize(7 * 5 * 4);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = std::uint8_t(i * 37 + 11);
    const auto path = temp("roundtrip.png");
    write_png(path, img);
    const RgbaImage back = read_png(path);
    EXPECT_EQ(back.width, 7u);
    EXPECT_EQ(back.height, 5u);
    EXPECT_EQ(back.pixels, img.pixels);
    EXPECT_FALSE(test::partial_left_beside(path));
    std::filesystem::remove(path);
}

// An opaque image is written as RGB (a quarter less to compress) and reads back the same, alpha 255.
TEST(Png, AnOpaqueImageIsWrittenAsRgbAndRoundTrips)
{
    RgbaImage img{64, 48, {}};
    img.pixels.resize(64 * 48 * 4);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = i % 4 == 3 ? 255 : std::uint8_t(i * 13 + (i / 256) * 7);
    const auto path = temp("opaque.png");
    write_png(path, img);
    const RgbaImage back = read_png(path);
    EXPECT_EQ(back.pixels, img.pixels);
    // the IHDR's colour type (byte 25 of the file): 2, RGB
    std::ifstream f(path, std::ios::binary);
    char header[26] = {};
    f.read(header, sizeof header);
    EXPECT_EQ(int(header[25]), 2);
    std::filesystem::remove(path);
}

TEST(Png, CorruptFileNamesTheFile)
{
    const auto path = temp("corrupt.png");
    {
        RgbaImage img{64, 64, std::vector<std::uint8_t>(64 * 64 * 4, 200)};
        write_png(path, img);
        // cut the file in half
        const auto size = std::filesystem::file_size(path);
        std::filesystem::resize_file(path, size / 2);
    }
    try {
        read_png(path);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
    std::ofstream(path) << "not a png";
    EXPECT_THROW(read_png(path), std::runtime_error);
    std::filesystem::remove(path);
}

TEST(Png, UnwritableFolderFailsWithoutLeavingAFile)
{
    const auto path = std::filesystem::path("/nonexistent-echosim-folder/x.png");
    RgbaImage img{2, 2, std::vector<std::uint8_t>(16, 1)};
    EXPECT_THROW(write_png(path, img), std::runtime_error);
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace echosim::io

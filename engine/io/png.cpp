#include "io/png.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include <png.h>

#include "io/partial_file.hpp"

namespace echosim::io {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why)
{
    throw std::runtime_error(path.string() + ": " + why);
}

void on_png_error(png_structp png, png_const_charp message)
{
    auto* error = static_cast<std::string*>(png_get_error_ptr(png));
    *error = message;
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// libpng's own writer says only "Write Error"; this one says why (a full disk: "File too large" or
// "No space left on device"), as every other writer does.
void write_to_file(png_structp png, png_bytep data, png_size_t n)
{
    auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
    if (std::fwrite(data, 1, n, file) != n) {
        char why[160];  // no std::string here: png_error jumps out, past any destructor
        std::snprintf(why, sizeof why, "write failed: %s", std::strerror(errno));
        png_error(png, why);  // on_png_error copies it before it jumps
    }
}

void flush_file(png_structp png) { std::fflush(static_cast<std::FILE*>(png_get_io_ptr(png))); }

}  // namespace

void write_png(const std::filesystem::path& path, const RgbaImage& image)
{
    if (image.width == 0 || image.height == 0 || image.pixels.size() != std::size_t(image.width) * image.height * 4)
        fail(path, "refusing to write an empty or inconsistent image");
    PartialFile<std::runtime_error> out(path);
    std::string error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        fail(path, "libpng could not start");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fail(path, "libpng: " + error);  // `out` removes the partial file
    }
    png_set_write_fn(png, out.get(), write_to_file, flush_file);
    // an opaque image (every frame the simulator draws) is written as RGB: a quarter less to
    // compress, and the alpha a reader would only drop
    bool opaque = true;
    for (std::size_t i = 3; i < image.pixels.size() && opaque; i += 4) opaque = image.pixels[i] == 255;
    png_set_IHDR(png, info, image.width, image.height, 8, opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // Speed over the last per cent of size: an exam writes hundreds of frames, and libpng's default
    // (trying all five row filters on every row, zlib at level 6) took half of its time. One filter
    // (Sub suits rendered images' smooth rows) and zlib's fastest level write about 3x as fast for
    // files about a fifth larger.
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_compression_level(png, 1);
    png_write_info(png, info);
    if (opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);  // the rows stay RGBA in memory: libpng drops the fourth byte
    for (std::uint32_t y = 0; y < image.height; ++y) png_write_row(png, image.at(0, y));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    out.commit();
}

RgbaImage read_png(const std::filesystem::path& path)
{
    File f(std::fopen(path.c_str(), "rb"));
    if (!f) fail(path, "cannot open: " + std::generic_category().message(errno));
    png_byte sig[8];
    if (std::fread(sig, 1, 8, f.get()) != 8 || png_sig_cmp(sig, 0, 8) != 0) fail(path, "not a PNG file");
    std::string error;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, nullptr);
        fail(path, "libpng could not start");
    }
    RgbaImage image;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        fail(path, "corrupt PNG: " + error);
    }
    png_init_io(png, f.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    // whatever the file holds, hand back 8-bit RGBA
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    image.width = png_get_image_width(png, info);
    image.height = png_get_image_height(png, info);
    image.pixels.resize(std::size_t(image.width) * image.height * 4);
    for (std::uint32_t y = 0; y < image.height; ++y) png_read_row(png, image.at(0, y), nullptr);
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return image;
}

}  // namespace echosim::io

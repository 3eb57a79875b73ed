#include "io/zlib_stream.hpp"

#include <algorithm>
#include <array>
#include <istream>

#define ZLIB_CONST
#include <zlib.h>

namespace echosim::io {
namespace {

constexpr std::size_t zlib_chunk = std::size_t(1) << 20;  // [bytes] file reads and writes around zlib

// z_streams ended on every path out, thrown or not (ending one never set up is harmless)
struct Inflater {
    z_stream z{};
    ~Inflater() { inflateEnd(&z); }
};
struct Deflater {
    z_stream z{};
    ~Deflater() { deflateEnd(&z); }
};

}  // namespace

Inflated inflate_exactly(std::istream& in, std::uint64_t bytes, std::uint64_t max_input)
{
    if (bytes > max_inflated_bytes(max_input))
        throw ZlibError(ZlibError::Kind::too_large, 0,
                        std::to_string(bytes) + " bytes cannot come from " + std::to_string(max_input) +
                            " compressed bytes: deflate inflates at most " + std::to_string(max_deflate_ratio) + " times");
    Inflater zs;
    if (inflateInit2(&zs.z, 15 + 32) != Z_OK)  // 32: gzip or zlib, from the stream's header
        throw ZlibError(ZlibError::Kind::cannot_start, 0, "zlib could not start");
    Inflated result;
    std::vector<std::uint8_t>& out = result.data;
    out.reserve(std::size_t(bytes));  // at most max_inflated_bytes(max_input), checked above
    std::vector<char> chunk(std::size_t(std::min<std::uint64_t>(zlib_chunk, max_input)));
    std::uint64_t input_left = max_input;
    std::array<Bytef, 4096> beyond;  // inflated bytes past the wanted ones, checked and dropped
    bool stream_end = false;
    while (!stream_end) {
        if (zs.z.avail_in == 0) {
            const auto want = std::streamsize(std::min<std::uint64_t>(chunk.size(), input_left));
            if (want == 0) break;
            in.read(chunk.data(), want);
            const auto got = in.gcount();
            if (got <= 0) break;
            input_left -= std::uint64_t(got);
            zs.z.next_in = reinterpret_cast<const Bytef*>(chunk.data());
            zs.z.avail_in = uInt(got);
        }
        const std::size_t before = out.size();
        const std::size_t grow = std::size_t(std::min<std::uint64_t>(bytes - before, 4 * zlib_chunk));
        out.resize(before + grow);
        zs.z.next_out = grow > 0 ? out.data() + before : beyond.data();
        zs.z.avail_out = grow > 0 ? uInt(grow) : uInt(beyond.size());
        const int rc = inflate(&zs.z, Z_NO_FLUSH);
        if (grow > 0) out.resize(before + grow - zs.z.avail_out);
        else result.beyond += beyond.size() - zs.z.avail_out;
        if (rc == Z_STREAM_END) stream_end = true;
        else if (rc != Z_OK && rc != Z_BUF_ERROR)
            throw ZlibError(ZlibError::Kind::corrupt, out.size(), zs.z.msg ? zs.z.msg : "zlib error " + std::to_string(rc));
    }
    if (!stream_end)
        throw ZlibError(ZlibError::Kind::input_ended, out.size(),
                        "the compressed data ends inside its stream, after " + std::to_string(out.size()) + " bytes");
    if (out.size() < bytes)
        throw ZlibError(ZlibError::Kind::ended_early, out.size(),
                        "the compressed stream holds " + std::to_string(out.size()) + " bytes, not " + std::to_string(bytes));
    return result;
}

void deflate_stream(std::span<const std::uint8_t> data, ZlibWrapper wrapper,
                    const std::function<void(std::span<const std::uint8_t>)>& write)
{
    Deflater zs;
    // level 3: volumes and sweeps are big, favour speed over the last few per cent; 15 + 16: gzip wrapper
    const int window_bits = wrapper == ZlibWrapper::gzip ? 15 + 16 : 15;
    if (deflateInit2(&zs.z, 3, Z_DEFLATED, window_bits, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw ZlibError(ZlibError::Kind::cannot_start, 0, "zlib could not start");
    std::vector<std::uint8_t> buf(zlib_chunk);
    std::size_t pos = 0;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        if (zs.z.avail_in == 0 && pos < data.size()) {
            const std::size_t take = std::min<std::size_t>(data.size() - pos, std::size_t(1) << 30);  // uInt-sized pieces
            zs.z.next_in = data.data() + pos;
            zs.z.avail_in = uInt(take);
            pos += take;
        }
        zs.z.next_out = buf.data();
        zs.z.avail_out = uInt(buf.size());
        rc = deflate(&zs.z, pos == data.size() ? Z_FINISH : Z_NO_FLUSH);
        if (rc == Z_STREAM_ERROR) throw ZlibError(ZlibError::Kind::compressing, 0, "zlib failed while compressing");
        if (const std::size_t n = buf.size() - zs.z.avail_out; n > 0) write(std::span(buf.data(), n));
    }
}

}  // namespace echosim::io

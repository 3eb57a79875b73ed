#include "io/zlib_stream.hpp"

#include <algorithm>
#include <array>
#include <istream>

#define ZLIB_CONST
#include <zlib.h>

namespace echosim::io {
namespace {

constexpr std::size_t zlib_chunk = std::size_t(1) << 20;  // [bytes] file reads and writes around zlib
constexpr std::uint64_t block_bytes = std::uint64_t(64) << 20;  // [bytes] the inflated output grows by at most this

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
    // The output grows in blocks as the stream delivers it, never ahead of the data: a header's size
    // is a claim until the stream bears it out (a 3 MB stream may claim 3 GiB within deflate's ratio,
    // and reserving that first cost 3 GiB for a stream that ended after a few bytes: issue 34).
    std::vector<std::vector<std::uint8_t>> blocks;
    std::uint64_t produced = 0;
    std::vector<char> chunk(std::size_t(std::min<std::uint64_t>(zlib_chunk, max_input)));
    std::uint64_t input_left = max_input;
    std::array<Bytef, 1> spare;  // where a byte past the wanted ones would go: one is enough to refuse
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
        if (produced < bytes && (blocks.empty() || blocks.back().size() == blocks.back().capacity())) {
            blocks.emplace_back();
            blocks.back().reserve(std::size_t(std::min<std::uint64_t>(bytes - produced, block_bytes)));
        }
        std::vector<std::uint8_t>* block = produced < bytes ? &blocks.back() : nullptr;
        const std::size_t before = block ? block->size() : 0;
        const std::size_t grow = block ? std::min<std::size_t>(block->capacity() - before, 4 * zlib_chunk) : 0;
        if (block) block->resize(before + grow);
        zs.z.next_out = block ? block->data() + before : spare.data();
        zs.z.avail_out = block ? uInt(grow) : uInt(spare.size());
        const int rc = inflate(&zs.z, Z_NO_FLUSH);
        if (block) {
            block->resize(before + grow - zs.z.avail_out);
            produced += grow - zs.z.avail_out;
        } else if (zs.z.avail_out == 0) {
            // the stream goes on past the bytes wanted: refused at its first byte, not inflated to
            // its end only to be counted (50 MB of trailing data took 25 s: issue 34)
            throw ZlibError(ZlibError::Kind::too_long, produced,
                            "the compressed data do not end after the " + std::to_string(bytes) + " bytes wanted: they hold more");
        }
        if (rc == Z_STREAM_END) stream_end = true;
        else if (rc != Z_OK && rc != Z_BUF_ERROR)
            throw ZlibError(ZlibError::Kind::corrupt, produced, zs.z.msg ? zs.z.msg : "zlib error " + std::to_string(rc));
    }
    if (!stream_end)
        throw ZlibError(ZlibError::Kind::input_ended, produced,
                        "the compressed data ends inside its stream, after " + std::to_string(produced) + " bytes");
    if (produced < bytes)
        throw ZlibError(ZlibError::Kind::ended_early, produced,
                        "the compressed stream holds " + std::to_string(produced) + " bytes, not " + std::to_string(bytes));
    // the whole stream is in: one vector of exactly its bytes (one block moves; more are copied in,
    // each freed once copied, so what is resident stays near the data's size)
    Inflated result;
    if (blocks.size() == 1) {
        result.data = std::move(blocks.front());
        return result;
    }
    result.data.reserve(std::size_t(bytes));
    for (std::vector<std::uint8_t>& b : blocks) {
        result.data.insert(result.data.end(), b.begin(), b.end());
        std::vector<std::uint8_t>().swap(b);
    }
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

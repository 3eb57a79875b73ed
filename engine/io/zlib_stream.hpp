// The one zlib path of the file formats that carry compressed data after a text header (NRRD's gzip
// encoding, PLUS/MetaImage CompressedData): a streaming inflate and a deflate.
//
// Inflating refuses, before anything is allocated, a size that no stream of the input's length can
// inflate to: deflate's densest code is 2 bits per 258-byte match, so a stream inflates to at most
// 1032 times its own size (zlib's technical notes). The output then grows in blocks of up to 64 MiB
// as the stream delivers bytes, never ahead of them, so a header that claims more than its stream
// holds costs only what the stream really held; the input is read in 1 MiB chunks, so the compressed
// data is never held whole. It runs on to the end of the stream (the checksum there is the only
// guard against corrupt data that still inflates) but refuses at the first byte past the bytes
// wanted: trailing data is never inflated only to be counted.
// Budget: memory, the bytes wanted plus 64 MiB while the blocks are joined (resident; the joined
// vector is touched as it fills), plus 1 MiB; time, one pass of inflate over at most the bytes
// wanted and the stream's own end.
// Failures are thrown as ZlibError with what the caller needs to say what went wrong in its own terms
// (file, field, the size its header gave).
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace echosim::io {

class ZlibError : public std::runtime_error {
public:
    enum class Kind {
        cannot_start,  // zlib could not be set up (out of memory)
        corrupt,       // not a zlib or gzip stream, or a wrong checksum; what() holds zlib's reason
        ended_early,   // the stream ended, checksum and all, before the bytes wanted: produced() says how many
        input_ended,   // the input (or its allowance) ended inside the stream, after produced() bytes
        compressing,   // deflate failed
        too_large,     // the bytes wanted exceed what the input could inflate to (max_inflated_bytes)
        too_long,      // the stream holds more than the bytes wanted (found at its first byte past them)
    };
    ZlibError(Kind kind, std::uint64_t produced, const std::string& what)
        : std::runtime_error(what), kind_(kind), produced_(produced)
    {
    }
    Kind kind() const { return kind_; }
    std::uint64_t produced() const { return produced_; }  // [bytes] inflated before the failure, at most the bytes wanted

private:
    Kind kind_;
    std::uint64_t produced_;
};

struct Inflated {
    std::vector<std::uint8_t> data;  // exactly the bytes wanted (a stream holding more is refused: too_long)
};

// deflate's largest ratio of inflated to compressed bytes (one literal, then matches of 258 bytes at
// 2 bits each)
inline constexpr std::uint64_t max_deflate_ratio = 1032;

// [bytes] the most that `compressed` bytes of a zlib or gzip stream can inflate to: the ratio, plus
// the first literal and a little for the smallest inputs; saturates rather than overflows.
constexpr std::uint64_t max_inflated_bytes(std::uint64_t compressed)
{
    constexpr std::uint64_t slack = 1024;
    constexpr std::uint64_t most = std::numeric_limits<std::uint64_t>::max();
    return compressed > (most - slack) / max_deflate_ratio ? most : compressed * max_deflate_ratio + slack;
}

// Inflates a zlib or gzip stream (told apart by its header) from `in`, reading at most `max_input`
// bytes of it (the caller passes the compressed size, or the bytes left in the file), into exactly
// `bytes` bytes; throws `too_large` before anything when `bytes` > max_inflated_bytes(max_input),
// `too_long` at the first inflated byte past `bytes`. Leaves `in` somewhere past the stream's end.
Inflated inflate_exactly(std::istream& in, std::uint64_t bytes,
                         std::uint64_t max_input = std::numeric_limits<std::uint64_t>::max());

enum class ZlibWrapper { zlib, gzip };

// Deflates `data` into one zlib or gzip stream, handed to `write` a chunk at a time (`write` may
// throw; the stream is then abandoned).
void deflate_stream(std::span<const std::uint8_t> data, ZlibWrapper wrapper,
                    const std::function<void(std::span<const std::uint8_t>)>& write);

}  // namespace echosim::io

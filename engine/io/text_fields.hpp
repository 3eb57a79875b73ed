// Small helpers shared by the readers and writers of formats with a text header (NRRD, PLUS/MetaImage
// sequences): the header's text, the file's messages, and the raw data after the header. Numbers are
// read by echosim::parse_number (core/parse_number.hpp), compressed data by io/zlib_stream.hpp.
#pragma once

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/printable_text.hpp"

namespace echosim::io::text {

inline std::string_view trim(std::string_view s)
{
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

inline std::vector<std::string_view> split_whitespace(std::string_view s)
{
    std::vector<std::string_view> out;
    std::size_t pos = 0;
    while ((pos = s.find_first_not_of(" \t", pos)) != std::string_view::npos) {
        const auto end = std::min(s.find_first_of(" \t", pos), s.size());
        out.push_back(s.substr(pos, end - pos));
        pos = end;
    }
    return out;
}

// The shortest form that reads back exactly.
inline std::string format_double(double v)
{
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, end) : std::string("nan");
}

// A value quoted for a message, cut short: enough to recognise a line, not a screenful of binary;
// its control characters escaped (core/printable_text.hpp: no terminal escape sequence echoed).
inline std::string quote_text(std::string_view s)
{
    constexpr std::size_t shown = 80;  // [bytes]
    return "'" + printable(s.substr(0, shown)) + (s.size() > shown ? "...'" : "'");
}

inline std::string upper(std::string_view s)
{
    std::string out(s);
    for (char& c : out) c = char(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

inline std::string lower(std::string_view s)
{
    std::string out(s);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// Each format throws its own exception type, its message opening with the file.
template <class Error>
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why)
{
    throw Error(path.string() + ": " + why);
}

// True when `path` names something that exists and is not a regular file: a device (/dev/zero, a
// terminal), a FIFO, a socket, a folder. Readers refuse them: such a "file" may never end, or block.
inline bool is_special_file(const std::filesystem::path& path)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    return !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
}

inline constexpr const char* not_regular_file = "not a regular file (a device, a FIFO or a folder)";

// The file, opened for reading; a missing file, or one that is not a regular file, throws Error naming it.
template <class Error>
std::ifstream open_binary(const std::filesystem::path& path)
{
    if (is_special_file(path)) fail<Error>(path, std::string(not_regular_file) + ": refusing to read it");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail<Error>(path, "cannot open: " + std::generic_category().message(errno));
    return in;
}

// The largest header a volume file (NRRD, MetaImage) may have [bytes]: a volume's header is some
// twenty lines; a larger one is junk, and kept field by field it cost 20 times its size (a 169 MB
// MetaImage header took 3.8 GB: issue 34). A sequence's header grows with its frames and is
// bounded by its own reader (plus_sequence.cpp) before it is parsed.
inline constexpr std::uint64_t max_volume_header_bytes = std::uint64_t(1) << 20;
inline constexpr std::uint64_t unbounded_header_bytes = ~std::uint64_t(0);

// Counts a header's bytes as its lines are read; throws Error naming the file once past `most`.
template <class Error>
void count_header_bytes(std::uint64_t& bytes, const std::string& line, std::uint64_t most, const std::filesystem::path& path)
{
    bytes += line.size() + 1;
    if (bytes > most)
        fail<Error>(path, "the header runs past " + std::to_string(most) + " bytes, more than a volume's header needs: not a volume's header");
}

// The longest header line the text-header readers (NRRD, PLUS) accept [bytes]: a longer "line" is
// binary junk, and reading on would only fill memory.
inline constexpr std::size_t max_header_line = std::size_t(1) << 20;

// One header line without its "\n" or "\r\n"; false at the end of the input. A line longer than
// max_header_line throws Error naming the file: binary data where a `format` header was expected.
template <class Error>
bool read_header_line(std::istream& in, std::string& line, const std::filesystem::path& path, std::string_view format)
{
    line.clear();
    std::streambuf* buf = in.rdbuf();
    for (;;) {
        const int c = buf->sbumpc();
        if (c == std::char_traits<char>::eof()) {
            in.setstate(std::ios::eofbit);
            if (line.empty()) return false;
            break;
        }
        if (c == '\n') break;
        if (line.size() >= max_header_line)
            fail<Error>(path, "header line longer than " + std::to_string(max_header_line >> 20) + " MiB: not a " +
                                  std::string(format) + " header");
        line.push_back(char(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
}

// Bytes left in `in` after its current position, or max when it cannot tell: what a header's
// sizes are checked against before anything is allocated for them. A stream already at its end (a
// header whose last line ends the file, without a newline) or failed has none left: tellg() cannot
// tell there, and "max" would let a header's claim through (issue 13, found by fuzz_volume).
inline std::uint64_t bytes_left(std::istream& in)
{
    if (!in.good()) return 0;
    const auto here = in.tellg();
    if (here == std::streampos(-1)) return std::numeric_limits<std::uint64_t>::max();
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(here);
    return end == std::streampos(-1) ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(end - here);
}

// Exactly `bytes` raw bytes from `in`; else nullopt, with `found` the bytes the input holds. Looks
// before allocating: a truncated file does not cost the memory its header claims.
inline std::optional<std::vector<std::uint8_t>> read_exactly(std::istream& in, std::uint64_t bytes, std::uint64_t& found)
{
    found = bytes_left(in);
    if (found < bytes) return std::nullopt;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(bytes));
    in.read(reinterpret_cast<char*>(out.data()), std::streamsize(bytes));
    found = std::uint64_t(in.gcount());
    if (found != bytes) return std::nullopt;
    return out;
}

}  // namespace echosim::io::text

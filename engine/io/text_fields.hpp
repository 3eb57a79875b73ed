// Small text helpers shared by the readers of text headers (NRRD, PLUS/MetaImage sequences).
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

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

// A whole token as a double ("nan" and "inf" parse, so callers can say "non-finite").
inline bool parse_double(std::string_view s, double& out)
{
    if (s.size() > 1 && s[0] == '+') s.remove_prefix(1);  // from_chars takes no '+'
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

// The shortest form that reads back exactly.
inline std::string format_double(double v)
{
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, end) : std::string("nan");
}

// The longest header line the text-header readers (NRRD, PLUS) accept [bytes]: a longer "line" is
// binary junk, and reading on would only fill memory.
inline constexpr std::size_t max_header_line = std::size_t(1) << 20;

// One header line without its "\n" or "\r\n"; false at the end of the input. A line longer than
// max_length calls too_long() (which throws): binary data where a header was expected.
template <class TooLong>
bool read_line(std::istream& in, std::string& line, std::size_t max_length, TooLong&& too_long)
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
        if (line.size() >= max_length) too_long();
        line.push_back(char(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
}

}  // namespace echosim::io::text

// Text that came from an input file, made safe to print (issue 34): a file's field can hold a
// terminal's escape sequence ("\x1b]0;owned\x07" retitles the window; others rewrite the screen,
// or worse on some terminals), and our messages quote what they refuse. Every byte a terminal could
// act on is written as a visible escape instead: the C0 controls (0x00..0x1f, newline and tab
// included: a quoted value is one line), DEL (0x7f), the C1 controls (U+0080..U+009F, and any byte
// that is not part of well-formed UTF-8, which an 8-bit terminal reads as C1: a lone 0x9b is CSI),
// each as \xHH of its bytes. Well-formed UTF-8 text passes as it is, so names in any language still
// read.
//
// The one place the readers' messages go through: InputFileError below, the base of every reader's
// error type (NRRD, MetaImage, PLUS sequence and configuration, transforms, tissue model,
// measurements), escapes its message when it is made, so no message that quotes a file can reach a
// terminal raw, whoever builds it. The trajectory reader, whose errors are std::invalid_argument,
// escapes what it quotes itself (device/trajectory.cpp).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace echosim {

inline std::string printable(std::string_view s)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(s.size());
    const auto escape = [&](unsigned char b) {
        out += "\\x";
        out += kHex[b >> 4];
        out += kHex[b & 15];
    };
    for (std::size_t i = 0; i < s.size();) {
        const auto b = static_cast<unsigned char>(s[i]);
        if (b < 0x20 || b == 0x7f) {
            escape(b);
            ++i;
            continue;
        }
        if (b < 0x80) {
            out += char(b);
            ++i;
            continue;
        }
        // a UTF-8 sequence: its length from the lead byte (C0, C1 and F5..FF lead nothing), its
        // continuation bytes 10xxxxxx, no overlong three- or four-byte forms, no surrogates, nothing
        // past U+10FFFF
        const std::size_t length = b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
        bool ok = length != 0 && i + length <= s.size();
        for (std::size_t k = 1; ok && k < length; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xc0) == 0x80;
        if (ok && length >= 3) {
            const auto b1 = static_cast<unsigned char>(s[i + 1]);
            ok = !(b == 0xe0 && b1 < 0xa0) && !(b == 0xed && b1 >= 0xa0) && !(b == 0xf0 && b1 < 0x90) && !(b == 0xf4 && b1 >= 0x90);
        }
        if (!ok) {
            escape(b);  // not UTF-8: one byte at a time
            ++i;
            continue;
        }
        // U+0080..U+009F, the C1 controls: C2 80..C2 9F
        if (b == 0xc2 && static_cast<unsigned char>(s[i + 1]) < 0xa0) {
            escape(b);
            escape(static_cast<unsigned char>(s[i + 1]));
        } else {
            out.append(s.substr(i, length));
        }
        i += length;
    }
    return out;
}

// The base of the readers' errors: the message as printable() leaves it (a message is one line;
// the readers write none with a line break of their own).
class InputFileError : public std::runtime_error {
public:
    explicit InputFileError(const std::string& what) : std::runtime_error(printable(what)) {}
    explicit InputFileError(const char* what) : std::runtime_error(printable(what)) {}
};

}  // namespace echosim

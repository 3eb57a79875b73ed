// The one number parser of the project: file headers (NRRD, PLUS), measurement tables, poses and
// command-line values all read their numbers here, so they all accept the same spellings.
//
// A token is parsed whole, as std::from_chars reads it (no blanks, no hexadecimal, no thousands
// separators; the caller trims), with a leading '+' accepted. Doubles accept "nan" and "inf" (any
// case, as from_chars does) so that the caller can say "not finite" rather than "not a number".
// Integers refuse fractions and exponents; unsigned types refuse a '-', even on zero.
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace echosim {

enum class NumberError : std::uint8_t {
    none,
    not_a_number,  // empty, a stray character, or not the whole token
    out_of_range,  // a well-formed number the type cannot hold (e.g. 1e999, or 2^64 for a std::uint64_t)
};

// What parse_number made of a token: true when it read the whole token; else why not.
struct ParsedNumber {
    NumberError error = NumberError::none;

    explicit constexpr operator bool() const { return error == NumberError::none; }
    constexpr bool out_of_range() const { return error == NumberError::out_of_range; }
};

// Parses the whole of `token` into `out` (double, float or any integer type); `out` is left as it was
// when the token is refused.
template <class T>
    requires(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
ParsedNumber parse_number(std::string_view token, T& out)
{
    // from_chars takes no '+': drop one, but not in front of a sign ("+-1") or of nothing ("+")
    if (!token.empty() && token.front() == '+') {
        token.remove_prefix(1);
        if (!token.empty() && (token.front() == '-' || token.front() == '+')) return {NumberError::not_a_number};
    }
    if (token.empty()) return {NumberError::not_a_number};
    T value{};
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (end != token.data() + token.size()) return {NumberError::not_a_number};  // "12x" is no number, even overflowing
    if (ec == std::errc::result_out_of_range) return {NumberError::out_of_range};
    if (ec != std::errc()) return {NumberError::not_a_number};
    out = value;
    return {};
}

}  // namespace echosim

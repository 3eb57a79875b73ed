#include "core/parse_number.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <gtest/gtest.h>

namespace echosim {
namespace {

template <class T>
std::optional<T> parsed(std::string_view token)
{
    T out{};
    if (parse_number(token, out)) return out;
    return std::nullopt;
}

TEST(ParseNumber, ReadsWholeDoubleTokens)
{
    double x = 0;
    EXPECT_TRUE(parse_number("42", x));
    EXPECT_EQ(x, 42.0);
    EXPECT_TRUE(parse_number("-3.25", x));
    EXPECT_EQ(x, -3.25);
    EXPECT_TRUE(parse_number("1e3", x));
    EXPECT_EQ(x, 1000.0);
    EXPECT_TRUE(parse_number(".5", x));
    EXPECT_EQ(x, 0.5);
    EXPECT_TRUE(parse_number("2.5E-1", x));
    EXPECT_EQ(x, 0.25);
    EXPECT_TRUE(parse_number("0.1", x));
    EXPECT_EQ(x, 0.1);  // correctly rounded, as written by to_chars
}

TEST(ParseNumber, AcceptsOneLeadingPlus)
{
    double x = 0;
    EXPECT_TRUE(parse_number("+7.5", x));
    EXPECT_EQ(x, 7.5);
    std::uint64_t u = 0;
    EXPECT_TRUE(parse_number("+12", u));
    EXPECT_EQ(u, 12u);
    int i = 0;
    EXPECT_TRUE(parse_number("+0", i));
    EXPECT_EQ(i, 0);
    // but not a plus alone, twice, or before another sign
    for (const char* token : {"+", "++1", "+-1", "-+1"}) {
        x = 99;
        EXPECT_FALSE(parse_number(token, x)) << token;
        EXPECT_EQ(x, 99.0) << token;
        i = 99;
        EXPECT_FALSE(parse_number(token, i)) << token;
        EXPECT_EQ(i, 99) << token;
    }
}

TEST(ParseNumber, RefusesPartialTokensAndLeavesTheOutputAlone)
{
    for (const char* token : {"", " ", "1.5x", "1 ", " 1", "1,2", "0x10", "12abc", "1e", "--1", "-", ".", "e5", "1_000"}) {
        double x = 99;
        const ParsedNumber r = parse_number(token, x);
        EXPECT_FALSE(r) << "'" << token << "'";
        EXPECT_EQ(r.error, NumberError::not_a_number) << "'" << token << "'";
        EXPECT_EQ(x, 99.0) << "'" << token << "'";
    }
    // a number too large for the type, followed by junk, is junk rather than an overflow
    std::uint64_t u = 5;
    EXPECT_EQ(parse_number("99999999999999999999999x", u).error, NumberError::not_a_number);
    EXPECT_EQ(u, 5u);
}

TEST(ParseNumber, RefusesOverflowSayingSo)
{
    double x = 99;
    for (const char* token : {"1e999", "-1e999", "+1e400"}) {
        const ParsedNumber r = parse_number(token, x);
        EXPECT_FALSE(r) << token;
        EXPECT_TRUE(r.out_of_range()) << token;
        EXPECT_EQ(x, 99.0) << token;
    }
    std::uint64_t u = 0;
    EXPECT_TRUE(parse_number("18446744073709551615", u));
    EXPECT_EQ(u, std::numeric_limits<std::uint64_t>::max());
    EXPECT_TRUE(parse_number("18446744073709551616", u).out_of_range());
    EXPECT_TRUE(parse_number("99999999999999999999999", u).out_of_range());
    EXPECT_EQ(u, std::numeric_limits<std::uint64_t>::max());
    int i = 0;
    EXPECT_TRUE(parse_number("-2147483648", i));
    EXPECT_EQ(i, std::numeric_limits<int>::min());
    EXPECT_TRUE(parse_number("2147483648", i).out_of_range());
    EXPECT_TRUE(parse_number("+2147483648", i).out_of_range());
    EXPECT_TRUE(parse_number("-2147483649", i).out_of_range());
    std::int64_t s = 0;
    EXPECT_TRUE(parse_number("-9223372036854775808", s));
    EXPECT_EQ(s, std::numeric_limits<std::int64_t>::min());
    EXPECT_TRUE(parse_number("9223372036854775808", s).out_of_range());
}

TEST(ParseNumber, ReadsNanAndInfinityForTheCallerToJudge)
{
    double x = 0;
    EXPECT_TRUE(parse_number("nan", x));
    EXPECT_TRUE(std::isnan(x));
    x = 0;
    EXPECT_TRUE(parse_number("NaN", x));
    EXPECT_TRUE(std::isnan(x));
    EXPECT_TRUE(parse_number("inf", x));
    EXPECT_EQ(x, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(parse_number("-inf", x));
    EXPECT_EQ(x, -std::numeric_limits<double>::infinity());
    x = 0;
    EXPECT_TRUE(parse_number("+Infinity", x));
    EXPECT_EQ(x, std::numeric_limits<double>::infinity());
    // integers have no such values
    std::int64_t s = 3;
    EXPECT_FALSE(parse_number("nan", s));
    EXPECT_FALSE(parse_number("inf", s));
    EXPECT_EQ(s, 3);
}

TEST(ParseNumber, IntegersRefuseFractionsAndUnsignedRefuseNegatives)
{
    for (const char* token : {"1.5", "1.0", "1e3", "2.", ".5"}) {
        int i = 7;
        EXPECT_EQ(parse_number(token, i).error, NumberError::not_a_number) << token;
        EXPECT_EQ(i, 7) << token;
        std::uint64_t u = 7;
        EXPECT_EQ(parse_number(token, u).error, NumberError::not_a_number) << token;
        EXPECT_EQ(u, 7u) << token;
    }
    for (const char* token : {"-1", "-0", "-18446744073709551615"}) {
        std::uint64_t u = 7;
        EXPECT_FALSE(parse_number(token, u)) << token;
        EXPECT_EQ(u, 7u) << token;
    }
    EXPECT_EQ(parsed<std::int64_t>("-7"), -7);
    EXPECT_EQ(parsed<int>("0042"), 42);  // leading zeros are decimal, not octal
    EXPECT_EQ(parsed<std::uint64_t>("12"), 12u);
    EXPECT_EQ(parsed<std::uint64_t>("-7"), std::nullopt);
}

}  // namespace
}  // namespace echosim

// Text from input files made safe to print (engine/core/printable_text.hpp): every byte a terminal
// acts on escaped as \xHH, well-formed UTF-8 kept. The readers' messages that quote it are checked
// in tests/io/printable_messages_test.cpp.
#include "core/printable_text.hpp"

#include <gtest/gtest.h>

namespace echosim {
namespace {

TEST(Printable, EscapesTheC0ControlsAndDel)
{
    EXPECT_EQ(printable("\x1b]0;owned\x07"), "\\x1b]0;owned\\x07");
    EXPECT_EQ(printable(std::string_view("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(printable("line\nnext\ttab\rback"), "line\\x0anext\\x09tab\\x0dback");
    EXPECT_EQ(printable("del\x7f"), "del\\x7f");
    EXPECT_EQ(printable("\x1f"), "\\x1f");
    EXPECT_EQ(printable(" ~ plain ASCII, quotes ' \" and a backslash \\ "), " ~ plain ASCII, quotes ' \" and a backslash \\ ");
}

TEST(Printable, EscapesTheC1ControlsInUtf8AndAsLoneBytes)
{
    EXPECT_EQ(printable("\xc2\x9b" "31m"), "\\xc2\\x9b31m");  // U+009B, CSI
    EXPECT_EQ(printable("\xc2\x80"), "\\xc2\\x80");
    EXPECT_EQ(printable("\x9b" "2J"), "\\x9b2J");  // CSI as an 8-bit terminal reads it
    EXPECT_EQ(printable("\xc2\xa0"), "\xc2\xa0");    // U+00A0, no control: kept
}

TEST(Printable, KeepsWellFormedUtf8AndEscapesWhatIsNot)
{
    EXPECT_EQ(printable("cuisse \xc3\xa9" "chographie \xe2\x86\x92 \xf0\x9f\xa6\xb5"), "cuisse \xc3\xa9" "chographie \xe2\x86\x92 \xf0\x9f\xa6\xb5");
    EXPECT_EQ(printable("\xc3"), "\\xc3");                  // cut short at the end
    EXPECT_EQ(printable("\xe2\x86" "A"), "\\xe2\\x86A");     // cut short before ASCII
    EXPECT_EQ(printable("\xc0\x9b"), "\\xc0\\x9b");          // overlong CSI
    EXPECT_EQ(printable("\xe0\x82\x9b"), "\\xe0\\x82\\x9b");  // overlong again
    EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
    EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // past U+10FFFF
    EXPECT_EQ(printable("\xff"), "\\xff");
}

}  // namespace
}  // namespace echosim

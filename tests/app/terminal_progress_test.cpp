#include "app/terminal_progress.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "app/volume_source.hpp"

namespace echosim::app {
namespace {

// What `write` writes to a stream, as text.
std::string written(const std::function<void(std::FILE*)>& write)
{
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* out = open_memstream(&buffer, &size);
    write(out);
    std::fclose(out);
    std::string text(buffer, size);
    std::free(buffer);
    return text;
}

// The progress of the default volume's making, as a terminal and as a log receive it.
std::string progress_text(bool terminal)
{
    return written([terminal](std::FILE* out) {
        TerminalProgress progress(std::string("echosim x: ") + kCaseVolumeProgress, out, terminal);
        const std::function<void(const std::string&, double)> copy = progress;  // as case_volume keeps it
        for (int i = 0; i <= 200; ++i) copy("imaging", i / 200.0);
        for (int i = 0; i <= 10; ++i) copy("filling", i / 10.0);
        progress.finish();
        progress.finish();  // a second finish adds nothing
    });
}

TEST(TerminalProgress, OnATerminalOneLineRewrittenInPlaceAndEnded)
{
    const std::string t = progress_text(true);
    // one update a whole percent, each back to the line's start and clearing what it leaves
    EXPECT_EQ(std::count(t.begin(), t.end(), '\r'), 101 + 11);
    EXPECT_NE(t.find("\rechosim x: making the default volume (once; it is cached): imaging  50 %\033[K"), std::string::npos) << t;
    EXPECT_EQ(std::count(t.begin(), t.end(), '\n'), 1);  // ended once, by finish()
    EXPECT_TRUE(t.ends_with("filling 100 %\033[K\n")) << t;
}

TEST(TerminalProgress, InALogWholeLinesAtEachQuarter)
{
    const std::string t = progress_text(false);
    EXPECT_EQ(t.find('\r'), std::string::npos);
    EXPECT_EQ(t.find('\033'), std::string::npos);
    std::string expected;
    for (const char* stage : {"imaging", "filling"})
        for (int q = 0; q <= 100; q += 25)
            expected += std::string("echosim x: making the default volume (once; it is cached): ") + stage + " " + (q < 10 ? "  " : q < 100 ? " " : "") +
                        std::to_string(q) + " %\n";
    EXPECT_EQ(t, expected);
}

TEST(TerminalProgress, NothingShownNothingEnded)
{
    // a cached volume: no progress was called
    EXPECT_EQ(written([](std::FILE* out) { TerminalProgress("echosim x: ", out, true).finish(); }), "");
}

}  // namespace
}  // namespace echosim::app

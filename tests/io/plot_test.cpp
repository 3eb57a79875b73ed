#include "io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

#include "io/bitmap_font.hpp"

#include <gtest/gtest.h>

namespace echosim::io {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr Rgba red{255, 0, 0, 255};

bool has_colour(const RgbaImage& image, int x, int y, Rgba c)
{
    const std::uint8_t* p = image.at(std::uint32_t(x), std::uint32_t(y));
    return p[0] == c.r && p[1] == c.g && p[2] == c.b && p[3] == c.a;
}

bool is_white(const RgbaImage& image, std::uint32_t x, std::uint32_t y)
{
    const std::uint8_t* p = image.at(x, y);
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

RgbaImage blank(std::uint32_t width, std::uint32_t height)
{
    return {width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4, 255)};
}

struct Box {
    int left = std::numeric_limits<int>::max();
    int top = std::numeric_limits<int>::max();
    int right = -1;  // inclusive
    int bottom = -1;
};

Box inked(const RgbaImage& image)
{
    Box b;
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            if (!is_white(image, x, y)) {
                b.left = std::min(b.left, int(x));
                b.top = std::min(b.top, int(y));
                b.right = std::max(b.right, int(x));
                b.bottom = std::max(b.bottom, int(y));
            }
    return b;
}

void expect_ticks(const std::vector<double>& got, const std::vector<double>& want)
{
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-12 * (1 + std::abs(want[i]))) << i;
}

TEST(NiceTicks, KnownRanges)
{
    expect_ticks(nice_ticks(0, 10, 6), {0, 2, 4, 6, 8, 10});
    expect_ticks(nice_ticks(0, 1, 5), {0, 0.5, 1});
    expect_ticks(nice_ticks(0, 1, 11), {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1});
    expect_ticks(nice_ticks(-3.7, 12.1, 8), {-2, 0, 2, 4, 6, 8, 10, 12});
    expect_ticks(nice_ticks(0.013, 0.047, 5), {0.02, 0.03, 0.04});
    expect_ticks(nice_ticks(0, 1e6, 5), {0, 5e5, 1e6});
    expect_ticks(nice_ticks(10, 0, 6), {0, 2, 4, 6, 8, 10});
}

TEST(NiceTicks, StepsAreOneTwoOrFiveTimesAPowerOfTen)
{
    const double ranges[][2] = {{0, 1}, {-1, 1}, {0.3, 0.7}, {-123.4, 5678.9}, {1e-7, 3e-7}, {999, 1001}, {-5e9, -1e9}};
    for (const auto& r : ranges)
        for (int most = 2; most <= 12; ++most) {
            const std::vector<double> ticks = nice_ticks(r[0], r[1], most);
            ASSERT_FALSE(ticks.empty());
            EXPECT_LE(int(ticks.size()), most);
            for (const double t : ticks) {
                EXPECT_GE(t, r[0] - 1e-9 * std::abs(r[0]));
                EXPECT_LE(t, r[1] + 1e-9 * std::abs(r[1]));
            }
            if (ticks.size() < 2) continue;
            const double step = ticks[1] - ticks[0];
            const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
            EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6)
                << "step " << step << " for [" << r[0] << ", " << r[1] << "]";
        }
}

TEST(NiceTicks, DegenerateInputs)
{
    expect_ticks(nice_ticks(5, 5, 5), {5});
    EXPECT_TRUE(nice_ticks(nan, 1, 5).empty());
    EXPECT_TRUE(nice_ticks(0, inf, 5).empty());
    EXPECT_TRUE(nice_ticks(-1e308, 1e308, 5).empty());  // the span overflows
    const std::vector<double> two = nice_ticks(0, 1, 0);
    EXPECT_FALSE(two.empty());
    EXPECT_LE(two.size(), 2u);
}

TEST(BitmapFont, WidthIsGlyphsPlusSpacing)
{
    EXPECT_EQ(text_width("ABC"), 3 * glyph_width + 2 * glyph_spacing);
    EXPECT_EQ(text_width("ABC", 3), 3 * (3 * glyph_width + 2 * glyph_spacing));
    EXPECT_EQ(text_width(""), 0);
    EXPECT_EQ(text_width("\xC2\xB0" "C"), text_width("?C"));  // "°C": one glyph per UTF-8 character
}

TEST(BitmapFont, DrawnTextFillsTheMeasuredBox)
{
    RgbaImage image = blank(100, 60);
    draw_text(image, 10, 5, "ABC", 2, {0, 0, 0, 255});
    const Box b = inked(image);
    EXPECT_EQ(b.left, 10);
    EXPECT_EQ(b.right, 10 + text_width("ABC", 2) - 1);
    EXPECT_EQ(b.top, 5);
    EXPECT_EQ(b.bottom, 5 + 7 * 2 - 1);  // capitals stay above the descender row

    RgbaImage rotated = blank(100, 60);
    draw_text(rotated, 10, 5, "ABC", 2, {0, 0, 0, 255}, TextDirection::up);
    const Box r = inked(rotated);
    EXPECT_EQ(r.left, 10);
    EXPECT_EQ(r.right, 10 + 7 * 2 - 1);
    EXPECT_EQ(r.top, 5);
    EXPECT_EQ(r.bottom, 5 + text_width("ABC", 2) - 1);
    // reading upwards from the bottom with the glyph tops facing left: A's rounded top-left corner
    // is the box's bottom-left pixel, with ink just above it and just right of it
    const int bottom = 5 + text_width("ABC", 2) - 1;
    EXPECT_TRUE(is_white(rotated, 10, std::uint32_t(bottom)));
    EXPECT_FALSE(is_white(rotated, 10, std::uint32_t(bottom - 2)));
    EXPECT_FALSE(is_white(rotated, 12, std::uint32_t(bottom)));
}

TEST(BitmapFont, EveryPrintableCharacterHasItsOwnGlyph)
{
    std::set<std::string> seen;  // the glyph's pixels as bytes (a vector key trips a GCC 12 false warning)
    for (char c = 33; c < 127; ++c) {
        RgbaImage image = blank(glyph_width, glyph_height);
        draw_text(image, 0, 0, std::string(1, c), 1, {0, 0, 0, 255});
        EXPECT_NE(image.pixels, blank(glyph_width, glyph_height).pixels) << "'" << c << "' draws nothing";
        EXPECT_TRUE(seen.insert(std::string(image.pixels.begin(), image.pixels.end())).second)
            << "'" << c << "' looks like another character";
    }
    RgbaImage space = blank(glyph_width, glyph_height);
    draw_text(space, 0, 0, " ", 1, {0, 0, 0, 255});
    EXPECT_EQ(space.pixels, blank(glyph_width, glyph_height).pixels);
}

TEST(BitmapFont, TextOffTheImageIsClipped)
{
    RgbaImage image = blank(20, 10);
    draw_text(image, -7, -4, "Hello, world", 3, {0, 0, 0, 255});
    draw_text(image, 15, 8, "Hello", 2, {0, 0, 0, 255}, TextDirection::up);
    EXPECT_EQ(image.pixels.size(), 20u * 10u * 4u);
}

Plot diagonal_plot()
{
    Plot plot;
    plot.title = "diagonal";
    plot.x_label = "x";
    plot.y_label = "y";
    plot.x_range = Range{0, 1};
    plot.y_range = Range{0, 1};
    plot.series.push_back({"line", red, {{0, 0}, {1, 1}}, SeriesStyle::line});
    return plot;
}

TEST(Plot, AreaMapsTheRangeEndsOntoItsFirstAndLastPixels)
{
    const PlotArea a = plot_area(diagonal_plot(), 400, 300);
    EXPECT_GT(a.left, 0);
    EXPECT_GT(a.top, 0);
    EXPECT_LT(a.left + a.width, 400);
    EXPECT_LT(a.top + a.height, 300);
    EXPECT_DOUBLE_EQ(a.to_pixel_x(0), a.left);
    EXPECT_DOUBLE_EQ(a.to_pixel_x(1), a.left + a.width - 1);
    EXPECT_DOUBLE_EQ(a.to_pixel_y(0), a.top + a.height - 1);
    EXPECT_DOUBLE_EQ(a.to_pixel_y(1), a.top);
}

TEST(Plot, LineFromOriginToOnePassesThroughTheDiagonal)
{
    Plot plot = diagonal_plot();
    plot.legend = Corner::none;  // its sample line is red too
    const RgbaImage image = render_plot(plot, 400, 300);
    ASSERT_EQ(image.width, 400u);
    ASSERT_EQ(image.height, 300u);
    const PlotArea a = plot_area(plot, 400, 300);
    for (const double t : {0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0}) {
        const int x = int(std::lround(a.to_pixel_x(t)));
        const int y = int(std::lround(a.to_pixel_y(t)));
        EXPECT_TRUE(has_colour(image, x, y, red)) << "t " << t;
        int mostly_red = 0;  // at least two pixels thick across the line
        for (int dx = -3; dx <= 3; ++dx) {
            const std::uint8_t* p = image.at(std::uint32_t(x + dx), std::uint32_t(y));
            mostly_red += p[0] > 200 && p[1] < 128;
        }
        EXPECT_GE(mostly_red, 2) << "t " << t;
    }
    for (const double t : {0.1, 0.3, 0.7, 0.9})  // the other diagonal stays clear
        EXPECT_FALSE(has_colour(image, int(std::lround(a.to_pixel_x(t))), int(std::lround(a.to_pixel_y(1 - t))), red));
}

TEST(Plot, DataOutsideFixedRangesStayInsideThePlotArea)
{
    Plot plot = diagonal_plot();
    plot.series[0].points = {{-10, -10}, {10, 10}, {1e300, -1e300}};
    plot.series[0].style = SeriesStyle::line_and_markers;
    plot.legend = Corner::none;
    const RgbaImage image = render_plot(plot, 400, 300);
    const PlotArea a = plot_area(plot, 400, 300);
    int inside = 0;
    for (int y = 0; y < 300; ++y)
        for (int x = 0; x < 400; ++x) {
            if (!has_colour(image, x, y, red)) continue;
            const bool in_area = x >= a.left && x < a.left + a.width && y >= a.top && y < a.top + a.height;
            EXPECT_TRUE(in_area) << x << ", " << y;
            inside += in_area;
        }
    EXPECT_GT(inside, a.width);  // the visible part of the diagonal was drawn
}

TEST(Plot, NonFiniteValuesBreakTheLineAndAreSkipped)
{
    Plot plot;
    plot.x_range = Range{0, 1};
    plot.y_range = Range{0, 1};
    plot.legend = Corner::none;
    plot.series.push_back({"", red, {{0, 0.5}, {0.4, 0.5}, {nan, 0.5}, {0.6, 0.5}, {1, 0.5}, {0.5, inf}}, SeriesStyle::line});
    const RgbaImage image = render_plot(plot, 300, 200);
    const PlotArea a = plot_area(plot, 300, 200);
    const int y = int(std::lround(a.to_pixel_y(0.5)));
    EXPECT_TRUE(has_colour(image, int(std::lround(a.to_pixel_x(0.2))), y, red));
    EXPECT_TRUE(has_colour(image, int(std::lround(a.to_pixel_x(0.8))), y, red));
    EXPECT_FALSE(has_colour(image, int(std::lround(a.to_pixel_x(0.5))), y, red));
}

TEST(Plot, NaNDataDoNotCrash)
{
    Plot plot;
    plot.title = "all NaN";
    plot.series.push_back({"nan", std::nullopt, {{nan, nan}, {nan, 1}, {1, nan}, {inf, -inf}}, SeriesStyle::line_and_markers});
    const std::vector<double> data = {nan, inf, -inf};
    plot.histograms.push_back(make_histogram(data, 5));
    plot.histograms.push_back(make_histogram_by_width(data, 0.5));
    plot.histograms.push_back({"broken", std::nullopt, {0, nan, 2}, {nan, 3}});
    plot.annotation = "MAE nan N";
    RgbaImage image;
    ASSERT_NO_THROW(image = render_plot(plot, 320, 240));
    EXPECT_EQ(image.pixels.size(), 320u * 240u * 4u);
    ASSERT_NO_THROW(render_plot_grid({plot, plot, plot}, 2, 320, 240));
}

TEST(Plot, EmptyPlotStillDrawsAxes)
{
    const Plot plot;
    const RgbaImage image = render_plot(plot, 320, 240);
    const PlotArea a = plot_area(plot, 320, 240);
    // the frame just outside the data rectangle, on all four sides
    const int mid_x = a.left + a.width / 2;
    const int mid_y = a.top + a.height / 2;
    EXPECT_FALSE(is_white(image, std::uint32_t(a.left - 1), std::uint32_t(mid_y)));
    EXPECT_FALSE(is_white(image, std::uint32_t(a.left + a.width), std::uint32_t(mid_y)));
    EXPECT_FALSE(is_white(image, std::uint32_t(mid_x), std::uint32_t(a.top - 1)));
    EXPECT_FALSE(is_white(image, std::uint32_t(mid_x), std::uint32_t(a.top + a.height)));
    // tick labels left of and below the frame
    int ink_left = 0, ink_below = 0;
    for (std::uint32_t y = 0; y < 240; ++y)
        for (std::uint32_t x = 0; x < 320; ++x) {
            if (is_white(image, x, y)) continue;
            ink_left += int(x) < a.left - 4;
            ink_below += int(y) > a.top + a.height + 4;
        }
    EXPECT_GT(ink_left, 20);
    EXPECT_GT(ink_below, 20);
}

TEST(Plot, BadArgumentsThrow)
{
    Plot plot = diagonal_plot();
    EXPECT_THROW(render_plot(plot, 0, 100), std::invalid_argument);
    plot.x_range = Range{1, 0};
    EXPECT_THROW(render_plot(plot, 100, 100), std::invalid_argument);
    plot.x_range = Range{0, nan};
    EXPECT_THROW(plot_area(plot, 100, 100), std::invalid_argument);
    plot.x_range = Range{2, 2};  // widened, not refused
    EXPECT_NO_THROW(render_plot(plot, 100, 100));
    EXPECT_THROW(render_plot_grid({plot}, 0, 100, 100), std::invalid_argument);
}

TEST(Plot, TinyImagesRender)
{
    for (const std::uint32_t size : {1u, 7u, 31u}) {
        const RgbaImage image = render_plot(diagonal_plot(), size, size);
        EXPECT_EQ(image.pixels.size(), std::size_t(size) * size * 4);
    }
}

int count_colour(const RgbaImage& image, Rgba c)
{
    int n = 0;
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x) n += has_colour(image, int(x), int(y), c);
    return n;
}

TEST(Plot, AutomaticLegendKeepsOffTheData)
{
    Plot plot;
    plot.x_range = Range{0, 1};
    plot.y_range = Range{0, 1};
    Series crowd{"data in the top right corner", red, {}, SeriesStyle::markers};
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 6; ++j) crowd.points.push_back({0.55 + 0.05 * i, 0.75 + 0.05 * j});
    plot.series.push_back(crowd);
    plot.legend = Corner::none;
    const int markers = count_colour(render_plot(plot, 400, 300), red);
    plot.legend = Corner::automatic;
    const int automatic = count_colour(render_plot(plot, 400, 300), red);
    plot.legend = Corner::top_right;
    const int on_top = count_colour(render_plot(plot, 400, 300), red);
    EXPECT_GT(automatic, markers);  // every marker plus the legend's sample
    EXPECT_LT(on_top, markers);     // shows that a badly placed legend would fail the check above
}

TEST(Histogram, BinsByCountAndByWidth)
{
    const std::vector<double> data = {0, 0.5, 1, 1.5, 2, 2.5, 3, 3.9, 4, nan, inf};
    const Histogram h = make_histogram(data, 4);
    ASSERT_EQ(h.edges.size(), 5u);
    ASSERT_EQ(h.counts.size(), 4u);
    EXPECT_DOUBLE_EQ(h.edges.front(), 0);
    EXPECT_DOUBLE_EQ(h.edges.back(), 4);
    EXPECT_EQ(h.counts, (std::vector<double>{2, 2, 2, 3}));  // the maximum joins the top bin

    const Histogram w = make_histogram_by_width(data, 1.5);
    EXPECT_EQ(w.edges, (std::vector<double>{0, 1.5, 3, 4.5}));
    EXPECT_EQ(w.counts, (std::vector<double>{3, 3, 3}));

    const Histogram one = make_histogram(std::vector<double>{7, 7, 7}, 3);
    EXPECT_EQ(one.counts, (std::vector<double>{0, 3, 0}));  // a single value sits mid-range

    EXPECT_THROW(make_histogram(data, 0), std::invalid_argument);
    EXPECT_THROW(make_histogram_by_width(data, 0), std::invalid_argument);
    EXPECT_THROW(make_histogram_by_width(data, nan), std::invalid_argument);
    EXPECT_THROW(make_histogram_by_width(data, 1e-12), std::invalid_argument);  // 4e12 bins
}

TEST(Histogram, TallestBarIsWhereTheDataConcentrate)
{
    std::vector<double> data;
    for (int i = 0; i <= 100; ++i) data.push_back(i * 0.1);        // 0..10, spread evenly
    for (int i = 0; i < 300; ++i) data.push_back(3.2 + i * 0.002);  // and a pile in [3, 4)
    Plot plot;
    plot.histograms.push_back(make_histogram(data, 10));
    plot.histograms[0].colour = red;
    plot.annotation = "MAE 1.05 N";
    const Histogram& h = plot.histograms[0];
    const auto tallest = std::max_element(h.counts.begin(), h.counts.end()) - h.counts.begin();
    EXPECT_EQ(tallest, 3);

    const RgbaImage image = render_plot(plot, 500, 400);
    const PlotArea a = plot_area(plot, 500, 400);
    // only the tallest bar reaches 90 % of its height
    const int y = int(std::lround(a.to_pixel_y(0.9 * h.counts[std::size_t(tallest)])));
    for (std::size_t i = 0; i < h.counts.size(); ++i) {
        const int x = int(std::lround(a.to_pixel_x((h.edges[i] + h.edges[i + 1]) / 2)));
        EXPECT_EQ(has_colour(image, x, y, red), i == std::size_t(tallest)) << "bin " << i;
        // every bar with data shows just above the axis
        EXPECT_EQ(has_colour(image, x, int(std::lround(a.to_pixel_y(0))) - 1, red), h.counts[i] > 1) << "bin " << i;
    }
}

TEST(PlotGrid, OnePanelPerPlotRowByRow)
{
    std::vector<Plot> plots(11, diagonal_plot());
    const RgbaImage image = render_plot_grid(plots, 4, 800, 600);
    ASSERT_EQ(image.width, 800u);
    ASSERT_EQ(image.height, 600u);
    // panels are 200 x 200; the twelfth cell has no plot and stays white
    for (std::uint32_t cell = 0; cell < 12; ++cell) {
        const std::uint32_t x0 = cell % 4 * 200, y0 = cell / 4 * 200;
        int red_pixels = 0;
        bool all_white = true;
        for (std::uint32_t y = y0; y < y0 + 200; ++y)
            for (std::uint32_t x = x0; x < x0 + 200; ++x) {
                red_pixels += has_colour(image, int(x), int(y), red);
                all_white = all_white && is_white(image, x, y);
            }
        EXPECT_EQ(red_pixels > 0, cell < 11) << "cell " << cell;
        EXPECT_EQ(all_white, cell == 11) << "cell " << cell;
    }
    // a panel is the same picture as the plot rendered alone at the panel's size
    const RgbaImage alone = render_plot(plots[5], 200, 200);
    for (std::uint32_t y = 0; y < 200; ++y)
        ASSERT_TRUE(std::equal(alone.at(0, y), alone.at(0, y) + 200 * 4, image.at(200, 200 + y))) << "row " << y;
}

}  // namespace
}  // namespace echosim::io

// Line plots and histograms rendered straight into an RgbaImage, so `echosim fit` can write its
// report figures as PNG without an external plotting program. Non-finite data are skipped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/bitmap_font.hpp"
#include "io/png.hpp"

namespace echosim::io {

struct Point {
    double x = 0;
    double y = 0;
};

enum class SeriesStyle { line, markers, line_and_markers };

// Without a colour, a series or histogram takes palette_colour(its index), counting the series
// first and then the histograms.
struct Series {
    std::string name;  // legend entry; empty keeps the series out of the legend
    std::optional<Rgba> colour;
    std::vector<Point> points;  // a non-finite point breaks a line rather than ending the series
    SeriesStyle style = SeriesStyle::line;
};

struct Histogram {
    std::string name;
    std::optional<Rgba> colour;
    std::vector<double> edges;   // bin i covers [edges[i], edges[i + 1]); the top bin also holds its upper edge
    std::vector<double> counts;  // edges.size() - 1 of them
};

// Both skip non-finite values. make_histogram spans the data's range with bin_count equal bins;
// make_histogram_by_width puts edges on multiples of bin_width. They throw std::invalid_argument
// for bin_count < 1, a bin width that is not positive and finite, or more than a million bins.
Histogram make_histogram(std::span<const double> data, int bin_count);
Histogram make_histogram_by_width(std::span<const double> data, double bin_width);

struct Range {
    double lo = 0;
    double hi = 1;
};

enum class Corner { automatic, top_left, top_right, bottom_left, bottom_right, none };

struct Plot {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<Series> series;
    std::vector<Histogram> histograms;  // drawn as filled bars from zero, beneath the series
    // Absent: fit the data with a little padding. Present: lo < hi, both finite (lo == hi is widened);
    // anything else makes the render functions throw std::invalid_argument.
    std::optional<Range> x_range;
    std::optional<Range> y_range;
    std::string annotation;  // boxed text in the plot area, e.g. "MAE 1.05 N"; '\n' starts a new line
    Corner legend = Corner::automatic;  // automatic: the corner where it hides the fewest data pixels
    int text_scale = 0;                 // glyph pixel size, at most 16; 0 picks one from the image size
};

Rgba palette_colour(std::size_t index);

// Ticks at multiples of the smallest step from {1, 2, 5} x 10^k that leaves at most max_ticks
// (at least 2) of them inside [lo, hi]. Empty when lo or hi is not finite; {lo} when lo == hi.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks);

// The data rectangle of a rendered plot: data value lo maps onto the first pixel, hi onto the last.
struct PlotArea {
    int left = 0;
    int top = 0;
    int width = 1;
    int height = 1;
    Range x;
    Range y;

    double to_pixel_x(double value) const { return left + (value - x.lo) / (x.hi - x.lo) * (width - 1); }
    double to_pixel_y(double value) const { return top + height - 1 - (value - y.lo) / (y.hi - y.lo) * (height - 1); }
};

// Where render_plot puts the data rectangle for this plot and image size, and the ranges it shows.
PlotArea plot_area(const Plot& plot, std::uint32_t width, std::uint32_t height);

// Both throw std::invalid_argument for a zero width or height. The grid fills row by row, one
// equal cell per plot; columns < 1 throws.
RgbaImage render_plot(const Plot& plot, std::uint32_t width, std::uint32_t height);
RgbaImage render_plot_grid(const std::vector<Plot>& plots, int columns, std::uint32_t width, std::uint32_t height);

}  // namespace echosim::io

#include "io/plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "io/raster.hpp"

namespace echosim::io {
namespace {

constexpr Rgba text_colour{30, 30, 30, 255};
constexpr Rgba frame_colour{70, 70, 70, 255};
constexpr Rgba grid_colour{226, 226, 226, 255};
constexpr Rgba box_border{160, 160, 160, 255};
constexpr Rgba box_fill{255, 255, 255, 255};
constexpr std::size_t max_bins = 1'000'000;

// Doubles this far outside any image are as good as infinitely far, and converting larger ones to
// int would be undefined.
int to_int(double v)
{
    constexpr double limit = 1e7;
    if (!(v > -limit)) return -int(limit);
    if (!(v < limit)) return int(limit);
    return int(std::lround(v));
}

bool finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

struct Rect {
    int left = 0;
    int top = 0;
    int width = 0;
    int height = 0;

    int right() const { return left + width; }  // one past the last column
    int bottom() const { return top + height; }
    bool contains(int x, int y) const { return x >= left && x < right() && y >= top && y < bottom(); }
};

Rect rect_of(const PlotArea& a) { return {a.left, a.top, a.width, a.height}; }

void fill_rect(RgbaImage& image, Rect r, Rgba colour) { io::fill_rect(image, r.left, r.top, r.width, r.height, colour); }

void outline_rect(RgbaImage& image, Rect r, Rgba colour)
{
    fill_rect(image, {r.left, r.top, r.width, 1}, colour);
    fill_rect(image, {r.left, r.bottom() - 1, r.width, 1}, colour);
    fill_rect(image, {r.left, r.top + 1, 1, r.height - 2}, colour);
    fill_rect(image, {r.right() - 1, r.top + 1, 1, r.height - 2}, colour);
}

Rgba darker(Rgba c) { return {std::uint8_t(c.r * 13 / 20), std::uint8_t(c.g * 13 / 20), std::uint8_t(c.b * 13 / 20), c.a}; }

// ---- binning -------------------------------------------------------------------------------------

struct Extent {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();

    void add(double v)
    {
        if (!std::isfinite(v)) return;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    bool empty() const { return lo > hi; }
};

Extent extent_of(std::span<const double> data)
{
    Extent e;
    for (const double v : data) e.add(v);
    return e;
}

Histogram binned(std::span<const double> data, double start, double width, std::size_t bins)
{
    Histogram h;
    h.edges.resize(bins + 1);
    for (std::size_t i = 0; i <= bins; ++i) h.edges[i] = start + double(i) * width;
    h.counts.assign(bins, 0.0);
    for (const double v : data) {
        if (!std::isfinite(v)) continue;
        const double index = std::floor((v - start) / width);
        h.counts[std::size_t(std::clamp(index, 0.0, double(bins - 1)))] += 1;
    }
    return h;
}

// ---- ranges and layout ---------------------------------------------------------------------------

// A range of zero width has no scale: give it one around its value.
Range widened(Range r)
{
    const double magnitude = std::max(std::abs(r.lo), std::abs(r.hi));
    if (r.hi - r.lo > magnitude * 1e-12) return r;
    const double half = magnitude > 0 ? magnitude * 0.05 : 0.5;
    const double mid = r.lo / 2 + r.hi / 2;
    return {mid - half, mid + half};
}

Range checked(const Range& r, const char* axis)
{
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || r.lo > r.hi || !std::isfinite(r.hi - r.lo))
        throw std::invalid_argument(std::string("plot: the fixed ") + axis + " range must be finite with lo <= hi");
    return widened(r);
}

Range padded(const Extent& e, double fraction)
{
    // keep the span finite even for data near the limits of double
    constexpr double big = 1e300;
    const Range r = e.empty() ? Range{0, 1} : widened({std::clamp(e.lo, -big, big), std::clamp(e.hi, -big, big)});
    const double pad = (r.hi - r.lo) * fraction;
    return {r.lo - pad, r.hi + pad};
}

std::pair<Range, Range> axis_ranges(const Plot& plot)
{
    const Range fixed_x = plot.x_range ? checked(*plot.x_range, "x") : Range{};
    const Range fixed_y = plot.y_range ? checked(*plot.y_range, "y") : Range{};
    // with x fixed, y fits only what is visible
    const auto visible = [&](double lo, double hi) { return !plot.x_range || (hi >= fixed_x.lo && lo <= fixed_x.hi); };
    Extent ex, ey;
    for (const Series& s : plot.series)
        for (const Point& p : s.points) {
            if (!finite(p)) continue;
            ex.add(p.x);
            if (visible(p.x, p.x)) ey.add(p.y);
        }
    bool bars = false;
    for (const Histogram& h : plot.histograms)
        for (std::size_t i = 0; i < h.counts.size() && i + 1 < h.edges.size(); ++i) {
            if (!std::isfinite(h.edges[i]) || !std::isfinite(h.edges[i + 1]) || !std::isfinite(h.counts[i])) continue;
            ex.add(h.edges[i]);
            ex.add(h.edges[i + 1]);
            if (!visible(h.edges[i], h.edges[i + 1])) continue;
            ey.add(h.counts[i]);
            ey.add(0);
            bars = true;
        }
    const Range x = plot.x_range ? fixed_x : padded(ex, 0.05);
    Range y = plot.y_range ? fixed_y : padded(ey, 0.05);
    // bars stand on the axis; the headroom keeps the tallest clear of a legend
    if (!plot.y_range && bars && ey.lo >= 0) y = {0, ey.hi > 0 ? ey.hi * 1.12 : 1};
    return {x, y};
}

// One format for a whole axis, so 0..1e6 does not read "500000" next to "1e+06".
std::vector<std::string> tick_labels(const std::vector<double>& ticks, const Range& r)
{
    const double step = ticks.size() >= 2 ? ticks[1] - ticks[0] : r.hi - r.lo;
    double largest = step;
    for (const double t : ticks) largest = std::max(largest, std::abs(t));
    const bool scientific = largest >= 1e6 || step < 1e-4;
    const int digits = std::clamp(int(std::floor(std::log10(largest)) - std::floor(std::log10(step))) + 1, 1, 15);
    const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
    std::vector<std::string> labels;
    for (double t : ticks) {
        if (t == 0) t = 0;  // no "-0.0"
        char text[40];
        if (scientific)
            std::snprintf(text, sizeof text, "%.*g", digits, t);
        else
            std::snprintf(text, sizeof text, "%.*f", decimals, t);
        labels.emplace_back(text);
    }
    return labels;
}

int widest(const std::vector<std::string>& labels, int scale)
{
    int most = 0;
    for (const std::string& label : labels) most = std::max(most, text_width(label, scale));
    return most;
}

struct Layout {
    PlotArea area;
    std::vector<double> x_ticks;
    std::vector<double> y_ticks;
    std::vector<std::string> x_labels;
    std::vector<std::string> y_labels;
    int scale = 1;
    int gap = 4;
    int tick = 3;
};

Layout make_layout(const Plot& plot, std::uint32_t width, std::uint32_t height)
{
    if (width == 0 || height == 0) throw std::invalid_argument("plot: the image must be at least 1x1 pixels");
    const auto [xr, yr] = axis_ranges(plot);
    // bounds that keep all the pixel arithmetic below in int
    const int w = int(std::min<std::uint32_t>(width, 1u << 24));
    const int h = int(std::min<std::uint32_t>(height, 1u << 24));
    Layout l;
    l.scale = plot.text_scale > 0 ? std::min(plot.text_scale, 16) : std::clamp(std::min(w, h) / 280, 1, 4);
    l.gap = 4 * l.scale;
    l.tick = 3 * l.scale;
    const int th = text_height(l.scale);
    PlotArea& a = l.area;
    a.x = xr;
    a.y = yr;
    // heights first: the y ticks depend on them, the left margin on the y tick labels
    a.top = plot.title.empty() ? 2 * l.gap : th + 2 * l.gap;
    const int bottom = 1 + l.tick + l.gap / 2 + th + (plot.x_label.empty() ? 0 : l.gap + th) + l.gap;
    a.height = std::max(1, h - a.top - bottom);
    l.y_ticks = nice_ticks(yr.lo, yr.hi, std::clamp(a.height / (3 * th), 2, 10));
    l.y_labels = tick_labels(l.y_ticks, yr);
    a.left = l.gap + (plot.y_label.empty() ? 0 : th + l.gap) + widest(l.y_labels, l.scale) + l.gap / 2 + l.tick + 1;
    a.width = std::max(1, w - a.left - 4 * l.gap);
    // fewer x ticks until their labels stop touching
    for (int most = std::clamp(a.width / (12 * l.scale), 2, 10);; --most) {
        l.x_ticks = nice_ticks(xr.lo, xr.hi, most);
        l.x_labels = tick_labels(l.x_ticks, xr);
        const double step = l.x_ticks.size() >= 2 ? l.x_ticks[1] - l.x_ticks[0] : xr.hi - xr.lo;
        const double spacing = step / (xr.hi - xr.lo) * (a.width - 1);
        if (most == 2 || widest(l.x_labels, l.scale) + 2 * l.gap <= spacing) break;
    }
    return l;
}

// ---- rasterising ---------------------------------------------------------------------------------

// Liang-Barsky: cut the segment to the box, so far-away endpoints cost nothing.
bool clip(double& ax, double& ay, double& bx, double& by, double x0, double y0, double x1, double y1)
{
    const double dx = bx - ax;
    const double dy = by - ay;
    double t0 = 0, t1 = 1;
    const std::array<std::pair<double, double>, 4> edges = {{{-dx, ax - x0}, {dx, x1 - ax}, {-dy, ay - y0}, {dy, y1 - ay}}};
    for (const auto& [p, q] : edges) {
        if (p == 0) {
            if (q < 0) return false;
            continue;
        }
        const double t = q / p;
        if (p < 0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    bx = ax + t1 * dx;
    by = ay + t1 * dy;
    ax = ax + t0 * dx;
    ay = ay + t0 * dy;
    return true;
}

// Coverage of one series inside a rectangle, combined by maximum so the segments and markers of a
// series do not darken where they overlap; composited once at the end.
class Mask {
public:
    explicit Mask(Rect bounds) : bounds_(bounds), cover_(std::size_t(bounds.width) * std::size_t(bounds.height), 0.0f) {}

    void cover(int x, int y, double amount)
    {
        if (amount <= 0 || !bounds_.contains(x, y)) return;
        float& c = cover_[std::size_t(y - bounds_.top) * std::size_t(bounds_.width) + std::size_t(x - bounds_.left)];
        c = std::max(c, float(std::min(amount, 1.0)));
    }

    // Round-capped, `half_width` either side of the centre line; coverage falls off over one pixel
    // at the edge, which smooths the staircase for free.
    void segment(double ax, double ay, double bx, double by, double half_width)
    {
        const double reach = half_width + 1;
        if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(bx) || !std::isfinite(by)) return;
        if (!clip(ax, ay, bx, by, bounds_.left - reach, bounds_.top - reach, bounds_.right() + reach,
                  bounds_.bottom() + reach))
            return;
        // walk the longer axis; across it only as far as the thickness reaches
        const bool steep = std::abs(by - ay) > std::abs(bx - ax);
        if (steep) {
            std::swap(ax, ay);
            std::swap(bx, by);
        }
        if (ax > bx) {
            std::swap(ax, bx);
            std::swap(ay, by);
        }
        const double dx = bx - ax;
        const double dy = by - ay;
        const double length2 = dx * dx + dy * dy;
        for (int u = to_int(ax - reach); u <= to_int(bx + reach); ++u) {
            const double along = dx > 0 ? std::clamp((u - ax) / dx, 0.0, 1.0) : 0.0;
            const double centre = ay + along * dy;
            for (int v = to_int(centre - 1.5 * reach); v <= to_int(centre + 1.5 * reach); ++v) {
                const double t = length2 > 0 ? std::clamp(((u - ax) * dx + (v - ay) * dy) / length2, 0.0, 1.0) : 0.0;
                const double distance = std::hypot(u - (ax + t * dx), v - (ay + t * dy));
                const double amount = half_width + 0.5 - distance;
                if (steep)
                    cover(v, u, amount);
                else
                    cover(u, v, amount);
            }
        }
    }

    void disk(double cx, double cy, double radius)
    {
        if (!std::isfinite(cx) || !std::isfinite(cy)) return;
        for (int y = to_int(cy - radius - 1); y <= to_int(cy + radius + 1); ++y)
            for (int x = to_int(cx - radius - 1); x <= to_int(cx + radius + 1); ++x)
                cover(x, y, radius + 0.5 - std::hypot(x - cx, y - cy));
    }

    // `occupied`, one byte a pixel of `bounds`, records what the legend should avoid; may be null.
    void composite(RgbaImage& image, Rgba colour, std::vector<std::uint8_t>* occupied) const
    {
        for (int y = 0; y < bounds_.height; ++y)
            for (int x = 0; x < bounds_.width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(bounds_.width) + std::size_t(x);
                if (cover_[i] <= 0) continue;
                blend_pixel(image, bounds_.left + x, bounds_.top + y, colour, cover_[i]);
                if (occupied) (*occupied)[i] = 1;
            }
    }

private:
    Rect bounds_;
    std::vector<float> cover_;
};

struct Style {
    double half_width;  // of lines
    double radius;      // of markers
};

Style style_for(int scale) { return {1.25 + 0.5 * (scale - 1), 2.5 + scale}; }

Rgba colour_of(const std::optional<Rgba>& chosen, std::size_t index) { return chosen.value_or(palette_colour(index)); }

void draw_series(RgbaImage& image, const PlotArea& a, const Series& s, Rgba colour, Style style,
                 std::vector<std::uint8_t>& occupied)
{
    Mask mask(rect_of(a));
    const bool lines = s.style != SeriesStyle::markers;
    const bool markers = s.style != SeriesStyle::line;
    const Point* previous = nullptr;
    for (const Point& p : s.points) {
        if (!finite(p)) {
            previous = nullptr;
            continue;
        }
        const double x = a.to_pixel_x(p.x);
        const double y = a.to_pixel_y(p.y);
        if (lines && previous)
            mask.segment(a.to_pixel_x(previous->x), a.to_pixel_y(previous->y), x, y, style.half_width);
        if (lines && !previous) mask.disk(x, y, style.half_width);  // a lone point still shows
        if (markers) mask.disk(x, y, style.radius);
        previous = &p;
    }
    mask.composite(image, colour, &occupied);
}

void draw_bars(RgbaImage& image, const PlotArea& a, const Histogram& h, Rgba colour, std::vector<std::uint8_t>& occupied)
{
    const Rect area = rect_of(a);
    const int base = to_int(a.to_pixel_y(std::clamp(0.0, a.y.lo, a.y.hi)));
    for (std::size_t i = 0; i < h.counts.size() && i + 1 < h.edges.size(); ++i) {
        if (!std::isfinite(h.edges[i]) || !std::isfinite(h.edges[i + 1]) || !std::isfinite(h.counts[i])) continue;
        if (h.counts[i] == 0) continue;
        const int x0 = to_int(a.to_pixel_x(std::min(h.edges[i], h.edges[i + 1])));
        const int x1 = to_int(a.to_pixel_x(std::max(h.edges[i], h.edges[i + 1])));
        const int top = to_int(a.to_pixel_y(h.counts[i]));
        const int y0 = std::max(std::min(top, base), area.top);
        const int y1 = std::min(std::max(top, base), area.bottom() - 1);
        const int left = std::max(x0, area.left);
        const int right = std::min(x1, area.right() - 1);
        if (left > right || y0 > y1) continue;
        const Rect bar{left, y0, right - left + 1, y1 - y0 + 1};
        fill_rect(image, bar, colour);
        // an edge only where it is the bar's own, not where the plot area cut it
        const Rgba edge = darker(colour);
        if (x0 == left) fill_rect(image, {left, y0, 1, bar.height}, edge);
        if (x1 == right) fill_rect(image, {right, y0, 1, bar.height}, edge);
        if (std::min(top, base) == y0) fill_rect(image, {left, y0, bar.width, 1}, edge);
        for (int y = bar.top; y < bar.bottom(); ++y)
            for (int x = bar.left; x < bar.right(); ++x)
                occupied[std::size_t(y - a.top) * std::size_t(a.width) + std::size_t(x - a.left)] = 1;
    }
}

// ---- decorations ---------------------------------------------------------------------------------

void draw_axes(RgbaImage& image, const Layout& l)
{
    const PlotArea& a = l.area;
    const Rect area = rect_of(a);
    for (const double t : l.x_ticks) {
        const int x = to_int(a.to_pixel_x(t));
        fill_rect(image, {x, area.top, 1, area.height}, grid_colour);
        fill_rect(image, {x, area.bottom() + 1, 1, l.tick}, frame_colour);
    }
    for (const double t : l.y_ticks) {
        const int y = to_int(a.to_pixel_y(t));
        fill_rect(image, {area.left, y, area.width, 1}, grid_colour);
        fill_rect(image, {area.left - 1 - l.tick, y, l.tick, 1}, frame_colour);
    }
}

void draw_labels(RgbaImage& image, const Plot& plot, const Layout& l)
{
    const PlotArea& a = l.area;
    const int s = l.scale;
    const int th = text_height(s);
    const int w = int(image.width);
    const int cap_middle = 7 * s / 2;  // centre of the letters, not counting the descender row
    outline_rect(image, {a.left - 1, a.top - 1, a.width + 2, a.height + 2}, frame_colour);

    const int x_labels_top = a.top + a.height + 1 + l.tick + l.gap / 2;
    for (std::size_t i = 0; i < l.x_ticks.size(); ++i) {
        const int tw = text_width(l.x_labels[i], s);
        const int x = std::clamp(to_int(a.to_pixel_x(l.x_ticks[i])) - tw / 2, 0, std::max(0, w - tw));
        draw_text(image, x, x_labels_top, l.x_labels[i], s, text_colour);
    }
    for (std::size_t i = 0; i < l.y_ticks.size(); ++i)
        draw_text(image, a.left - 1 - l.tick - l.gap / 2 - text_width(l.y_labels[i], s),
                  to_int(a.to_pixel_y(l.y_ticks[i])) - cap_middle, l.y_labels[i], s, text_colour);
    const auto centred = [&](const std::string& text) {
        const int tw = text_width(text, s);
        return std::clamp(a.left + a.width / 2 - tw / 2, 0, std::max(0, w - tw));
    };
    if (!plot.title.empty()) draw_text(image, centred(plot.title), l.gap, plot.title, s, text_colour);
    if (!plot.x_label.empty()) draw_text(image, centred(plot.x_label), x_labels_top + th + l.gap, plot.x_label, s, text_colour);
    if (!plot.y_label.empty()) {
        const int y = std::max(0, a.top + a.height / 2 - text_width(plot.y_label, s) / 2);
        draw_text(image, l.gap, y, plot.y_label, s, text_colour, TextDirection::up);
    }
}

constexpr std::array<Corner, 4> corner_preference = {Corner::top_right, Corner::top_left, Corner::bottom_right,
                                                     Corner::bottom_left};

Rect box_at(const Layout& l, Corner corner, int width, int height)
{
    const PlotArea& a = l.area;
    const bool right = corner == Corner::top_right || corner == Corner::bottom_right;
    const bool bottom = corner == Corner::bottom_left || corner == Corner::bottom_right;
    return {right ? a.left + a.width - l.gap - width : a.left + l.gap,
            bottom ? a.top + a.height - l.gap - height : a.top + l.gap, width, height};
}

// The requested corner, or else the one where the box hides the fewest data pixels.
Corner place_box(const Layout& l, Corner wanted, Corner taken, int width, int height,
                 const std::vector<std::uint8_t>& occupied)
{
    if (wanted != Corner::automatic) return wanted;
    const Rect area = rect_of(l.area);
    Corner best = Corner::none;
    std::size_t best_hidden = std::numeric_limits<std::size_t>::max();
    for (const Corner c : corner_preference) {
        if (c == taken) continue;
        const Rect r = box_at(l, c, width, height);
        std::size_t hidden = 0;
        for (int y = std::max(r.top, area.top); y < std::min(r.bottom(), area.bottom()); ++y)
            for (int x = std::max(r.left, area.left); x < std::min(r.right(), area.right()); ++x)
                hidden += occupied[std::size_t(y - area.top) * std::size_t(area.width) + std::size_t(x - area.left)];
        if (hidden < best_hidden) {
            best = c;
            best_hidden = hidden;
        }
    }
    return best;
}

struct LegendEntry {
    std::string_view name;
    Rgba colour;
    const Series* series;  // null for a histogram
};

// Returns the corner used, so the annotation can keep out of it.
Corner draw_legend(RgbaImage& image, const Plot& plot, const Layout& l, const std::vector<std::uint8_t>& occupied)
{
    std::vector<LegendEntry> entries;
    std::size_t index = 0;
    for (const Series& s : plot.series)
        if (const Rgba c = colour_of(s.colour, index++); !s.name.empty()) entries.push_back({s.name, c, &s});
    for (const Histogram& h : plot.histograms)
        if (const Rgba c = colour_of(h.colour, index++); !h.name.empty()) entries.push_back({h.name, c, nullptr});
    if (entries.empty() || plot.legend == Corner::none) return Corner::none;

    const int s = l.scale;
    const Style style = style_for(s);
    const int pad = 3 * s + 1;
    const int sample = 18 * s;
    const int row = std::max(text_height(s), int(2 * style.radius) + 1) + 2 * s;
    int names = 0;
    for (const LegendEntry& e : entries) names = std::max(names, text_width(e.name, s));
    const int width = pad + sample + l.gap + names + pad;
    const int height = 2 * pad + int(entries.size()) * row - 2 * s;
    const Corner corner = place_box(l, plot.legend, Corner::none, width, height, occupied);
    const Rect box = box_at(l, corner, width, height);
    fill_rect(image, box, box_fill);
    outline_rect(image, box, box_border);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const LegendEntry& e = entries[i];
        const int top = box.top + pad + int(i) * row;
        const double middle = top + (row - 2 * s) / 2.0;
        Mask mask({box.left + pad, top, sample, row});
        if (!e.series) {
            const int side = text_height(s);
            fill_rect(image, {box.left + pad + (sample - side) / 2, int(middle) - side / 2, side, side}, e.colour);
        } else {
            if (e.series->style != SeriesStyle::markers)
                mask.segment(box.left + pad + style.half_width, middle, box.left + pad + sample - 1 - style.half_width,
                             middle, style.half_width);
            if (e.series->style != SeriesStyle::line) mask.disk(box.left + pad + (sample - 1) / 2.0, middle, style.radius);
            mask.composite(image, e.colour, nullptr);
        }
        draw_text(image, box.left + pad + sample + l.gap, int(middle) - 7 * s / 2, e.name, s, text_colour);
    }
    return corner;
}

void draw_annotation(RgbaImage& image, const Plot& plot, const Layout& l, Corner legend,
                     const std::vector<std::uint8_t>& occupied)
{
    if (plot.annotation.empty()) return;
    std::vector<std::string_view> lines;
    for (std::string_view rest = plot.annotation;;) {
        const std::size_t end = rest.find('\n');
        lines.push_back(rest.substr(0, end));
        if (end == std::string_view::npos) break;
        rest.remove_prefix(end + 1);
    }
    const int s = l.scale;
    const int pad = 3 * s + 1;
    const int row = text_height(s) + 2 * s;
    int widest = 0;
    for (const std::string_view line : lines) widest = std::max(widest, text_width(line, s));
    const int width = 2 * pad + widest;
    const int height = 2 * pad + int(lines.size()) * row - 2 * s;
    // an explicit legend corner pins the legend; the annotation then takes the best of the others
    const Corner corner = place_box(l, Corner::automatic, legend, width, height, occupied);
    const Rect box = box_at(l, corner, width, height);
    fill_rect(image, box, box_fill);
    outline_rect(image, box, box_border);
    for (std::size_t i = 0; i < lines.size(); ++i)
        draw_text(image, box.left + pad, box.top + pad + int(i) * row, lines[i], s, text_colour);
}

}  // namespace

Histogram make_histogram(std::span<const double> data, int bin_count)
{
    if (bin_count < 1 || std::size_t(bin_count) > max_bins)
        throw std::invalid_argument("histogram: the bin count must be 1.." + std::to_string(max_bins) + ", not " +
                                    std::to_string(bin_count));
    const Extent e = extent_of(data);
    Range r = e.empty() ? Range{0, 1} : Range{e.lo, e.hi};
    if (r.lo == r.hi) r = {r.lo - 0.5, r.hi + 0.5};
    // hi / n - lo / n stays finite where hi - lo would not
    return binned(data, r.lo, r.hi / bin_count - r.lo / bin_count, std::size_t(bin_count));
}

Histogram make_histogram_by_width(std::span<const double> data, double bin_width)
{
    if (!(bin_width > 0) || !std::isfinite(bin_width))
        throw std::invalid_argument("histogram: the bin width must be positive and finite, not " + std::to_string(bin_width));
    const Extent e = extent_of(data);
    if (e.empty()) return binned(data, 0, bin_width, 1);
    const double start = std::floor(e.lo / bin_width) * bin_width;
    const double bins = std::floor((e.hi - start) / bin_width) + 1;
    if (!(bins <= double(max_bins)))
        throw std::invalid_argument("histogram: bin width " + std::to_string(bin_width) + " would make more than " +
                                    std::to_string(max_bins) + " bins");
    return binned(data, start, bin_width, std::size_t(bins));
}

Rgba palette_colour(std::size_t index)
{
    // distinct on white, strongest contrast first; twelve so the fit report's 11 points do not repeat
    static constexpr std::array<Rgba, 12> colours = {{{0, 90, 181, 255},
                                                      {220, 110, 0, 255},
                                                      {0, 140, 80, 255},
                                                      {200, 30, 60, 255},
                                                      {110, 70, 170, 255},
                                                      {0, 150, 170, 255},
                                                      {140, 90, 40, 255},
                                                      {90, 90, 90, 255},
                                                      {210, 60, 170, 255},
                                                      {125, 130, 0, 255},
                                                      {90, 160, 240, 255},
                                                      {20, 20, 20, 255}}};
    return colours[index % colours.size()];
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks)
{
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (lo > hi) std::swap(lo, hi);
    if (lo == hi) return {lo};
    const double span = hi - lo;
    if (!std::isfinite(span)) return {};
    max_ticks = std::max(max_ticks, 2);
    // from a decade below the step that would give max_ticks, try 1, 2, 5 times each decade
    double decade = std::pow(10.0, std::floor(std::log10(span / max_ticks)) - 1);
    for (;; decade *= 10) {
        for (const double multiple : {1.0, 2.0, 5.0}) {
            const double step = multiple * decade;
            // a little slack so a bound that is a multiple of step in decimal counts as one
            const double first = std::ceil(lo / step - 1e-9);
            const double last = std::floor(hi / step + 1e-9);
            if (!(last - first + 1 <= max_ticks)) continue;
            std::vector<double> ticks;
            for (double k = first; k <= last; ++k) {
                const double t = k * step;  // not accumulated, so 0.1 steps stay clean
                ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
            }
            return ticks;
        }
    }
}

PlotArea plot_area(const Plot& plot, std::uint32_t width, std::uint32_t height)
{
    return make_layout(plot, width, height).area;
}

RgbaImage render_plot(const Plot& plot, std::uint32_t width, std::uint32_t height)
{
    const Layout l = make_layout(plot, width, height);
    RgbaImage image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4, 255)};
    draw_axes(image, l);
    const Style style = style_for(l.scale);
    std::vector<std::uint8_t> occupied(std::size_t(l.area.width) * std::size_t(l.area.height), 0);
    std::size_t index = plot.series.size();  // histograms take the palette after the series
    for (const Histogram& h : plot.histograms) draw_bars(image, l.area, h, colour_of(h.colour, index++), occupied);
    index = 0;
    for (const Series& s : plot.series) draw_series(image, l.area, s, colour_of(s.colour, index++), style, occupied);
    draw_labels(image, plot, l);
    const Corner legend = draw_legend(image, plot, l, occupied);
    draw_annotation(image, plot, l, legend, occupied);
    return image;
}

RgbaImage render_plot_grid(const std::vector<Plot>& plots, int columns, std::uint32_t width, std::uint32_t height)
{
    if (columns < 1) throw std::invalid_argument("plot grid: columns must be at least 1, not " + std::to_string(columns));
    if (width == 0 || height == 0) throw std::invalid_argument("plot grid: the image must be at least 1x1 pixels");
    RgbaImage image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4, 255)};
    const std::size_t cols = std::size_t(columns);
    const std::size_t rows = (plots.size() + cols - 1) / cols;
    for (std::size_t i = 0; i < plots.size(); ++i) {
        // cell edges by rounding down, so the cells tile the image exactly
        const auto edge = [](std::size_t k, std::size_t n, std::uint32_t size) { return std::uint32_t(k * size / n); };
        const std::uint32_t x0 = edge(i % cols, cols, width), x1 = edge(i % cols + 1, cols, width);
        const std::uint32_t y0 = edge(i / cols, rows, height), y1 = edge(i / cols + 1, rows, height);
        if (x1 == x0 || y1 == y0) continue;
        const RgbaImage cell = render_plot(plots[i], x1 - x0, y1 - y0);
        for (std::uint32_t y = 0; y < cell.height; ++y)
            std::copy_n(cell.at(0, y), std::size_t(cell.width) * 4, image.at(x0, y0 + y));
    }
    return image;
}

}  // namespace echosim::io

#include "exam/station_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "exam/report_images.hpp"
#include "exam/report_svg.hpp"
#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "io/raster.hpp"

namespace echosim::exam {
namespace {


struct Thumb {
    std::string name, figures;  // the caption's two lines
    std::optional<io::RgbaImage> image;
    std::string why;
    StationStatus status = StationStatus::covered;
};

}  // namespace

io::RgbaImage station_sheet(const ExamReport& r, const std::filesystem::path& dir, const SheetStyle& style)
{
    std::vector<Thumb> thumbs;
    for (std::size_t i = 0; i < r.stations.size(); ++i) {
        const StationResult& s = r.stations[i];
        if (s.image_png.empty()) continue;
        const std::string lumen = s.deepest_press_at_s >= 0 ? fixed(100 * s.collapse_ratio, 0) + " %  " : std::string("not pressed  ");
        Thumb t{s.name, lumen + fixed(s.peak_force_N, 1) + " N", std::nullopt, "", station_status(r, i)};
        const StationImage file = read_station_image(dir, s.image_png);
        if (file.png.empty()) {
            t.why = file.why;
        } else {
            try {
                t.image = io::read_png(station_image_path(dir, s.image_png));
            } catch (const std::exception&) {
                t.why = "not a readable PNG";
            }
        }
        thumbs.push_back(std::move(t));
    }
    io::RgbaImage img;
    if (thumbs.empty() || style.width <= 0) return img;

    // a thumbnail's box: the widest that fits a row, as tall as the images' aspect (the first
    // readable one's; a scanner's images are alike), with its caption under it
    double aspect = 1.25;  // height / width: a 40 x 50 mm image
    for (const Thumb& t : thumbs)
        if (t.image && t.image->width > 0) {
            aspect = double(t.image->height) / t.image->width;
            break;
        }
    const int line_h = io::text_height(style.caption_scale) + 2 * style.caption_scale;
    const int caption_h = 2 * line_h + 6;
    const int frame = style.status_frames ? 3 : 0;  // [px] the status frame's, round each thumbnail
    const int width = style.width - 2 * frame;
    const int n = int(thumbs.size());
    const auto box_height = [&](int w) {
        const int h = int(std::lround(w * aspect));
        return style.thumb_max_height > 0 ? std::min(h, style.thumb_max_height) : h;
    };
    int per_row = std::max(1, (width + style.gap) / (style.thumb_width + style.gap));
    int thumb_w = std::min(style.thumb_width, (width + style.gap) / per_row - style.gap);
    if (style.max_height > 0) {
        // the number of columns that gives the largest thumbnails whose rows still fit
        int best_w = 0, best_per_row = n;
        for (int cols = 1; cols <= n; ++cols) {
            const int rows = (n + cols - 1) / cols;
            const int by_width = (width + style.gap) / cols - style.gap;
            const int by_height = int((double(style.max_height - 2 * frame + style.gap) / rows - style.gap - caption_h) / aspect);
            const int w = std::min({style.thumb_width, by_width, by_height});
            if (w > best_w) best_w = w, best_per_row = cols;
        }
        thumb_w = std::max(best_w, 8);
        per_row = best_per_row;
    }
    const int thumb_h = box_height(thumb_w);
    const int rows = (n + per_row - 1) / per_row;
    img.width = std::uint32_t(style.width);
    img.height = std::uint32_t(rows * (thumb_h + caption_h) + (rows - 1) * style.gap + 2 * frame);
    img.pixels.resize(std::size_t(img.width) * img.height * 4);
    for (std::size_t p = 0; p < img.pixels.size(); p += 4)
        img.pixels[p] = style.paper.r, img.pixels[p + 1] = style.paper.g, img.pixels[p + 2] = style.paper.b, img.pixels[p + 3] = style.paper.a;
    for (int k = 0; k < n; ++k) {
        const Thumb& t = thumbs[std::size_t(k)];
        const int x = frame + (k % per_row) * (thumb_w + style.gap), y = frame + (k / per_row) * (thumb_h + caption_h + style.gap);
        if (t.image && t.image->width > 0) {
            // the image's own aspect within the box (narrower where the box's height is capped)
            const int h = std::min(thumb_h, int(std::lround(double(thumb_w) * t.image->height / t.image->width)));
            const int w = std::min(thumb_w, int(std::lround(double(h) * t.image->width / std::max(1u, t.image->height))));
            if (frame > 0) io::fill_rect(img, x - frame, y - frame, w + 2 * frame, h + 2 * frame, status_rgba(t.status));
            io::blit_scaled(img, *t.image, x, y, w, h);
        } else {
            if (frame > 0) io::fill_rect(img, x - frame, y - frame, thumb_w + 2 * frame, thumb_h + 2 * frame, status_rgba(t.status));
            io::fill_rect(img, x, y, thumb_w, thumb_h, style.placeholder);
            io::draw_text(img, x + 6, y + 22, io::fit_text(t.why, thumb_w - 12, 1), 1, style.muted);
        }
        io::draw_text(img, x, y + thumb_h + 6, io::fit_text(t.name, thumb_w, style.caption_scale), style.caption_scale, style.ink);
        io::draw_text(img, x, y + thumb_h + 6 + line_h, io::fit_text(t.figures, thumb_w, style.caption_scale), style.caption_scale, style.muted);
    }
    return img;
}

}  // namespace echosim::exam

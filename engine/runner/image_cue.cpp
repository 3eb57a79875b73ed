#include "runner/image_cue.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

#include "io/bitmap_font.hpp"

namespace echosim::runner {

CueText cue_text(ImageCue cue)
{
    switch (cue) {
    case ImageCue::no_contact: return {"NO CONTACT", "place the probe on the skin"};
    case ImageCue::outside_region: return {"OUTSIDE THE MODELLED REGION", "slide back over the thigh"};
    case ImageCue::volume_pending: return {"IMAGES BEING MADE", "once; the start screen shows how far"};
    case ImageCue::none: break;
    }
    return {};
}

ImageCue image_cue(const echo::EchoFrame& frame, const echo::ImagePlane& plane, const io::Volume& grid)
{
    // a 5 x 5 grid of pixel centres over the image, from its corners in
    const glm::dmat4 to_world = echo::pixel_to_world(plane, frame.face);
    int inside = 0;
    constexpr int n = 5;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double c = (plane.columns - 1) * double(i) / (n - 1), r = (plane.rows - 1) * double(j) / (n - 1);
            const glm::dvec3 world(to_world * glm::dvec4(c, r, 0.0, 1.0));
            const glm::dvec3 ijk = grid.world_to_index(world);
            bool in = true;
            for (int a = 0; a < 3; ++a) in = in && ijk[a] >= -0.5 && ijk[a] <= double(grid.size[std::size_t(a)]) - 0.5;
            inside += in ? 1 : 0;
        }
    if (2 * inside < n * n) return ImageCue::outside_region;
    if (frame.columns.empty()) return ImageCue::no_contact;
    return ImageCue::none;
}

io::RgbaImage cue_banner(ImageCue cue)
{
    io::RgbaImage out;
    if (cue == ImageCue::none) return out;
    const CueText text = cue_text(cue);
    constexpr int big = 3, small = 2, pad = 10, gap = 8;
    const int width = std::max(io::text_width(text.headline, big), io::text_width(text.hint, small)) + 2 * pad;
    const int height = io::text_height(big) + gap + io::text_height(small) + 2 * pad;
    out.width = std::uint32_t(width);
    out.height = std::uint32_t(height);
    out.pixels.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    // dark grey with an amber frame, amber headline, white hint: readable over any echo texture
    const io::Rgba back{24, 24, 24, 255}, amber{255, 190, 40, 255}, white{235, 235, 235, 255};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool edge = x < 2 || y < 2 || x >= width - 2 || y >= height - 2;
            const io::Rgba c = edge ? amber : back;
            std::uint8_t* p = out.at(std::uint32_t(x), std::uint32_t(y));
            p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
        }
    io::draw_text(out, (width - io::text_width(text.headline, big)) / 2, pad, text.headline, big, amber);
    io::draw_text(out, (width - io::text_width(text.hint, small)) / 2, pad + io::text_height(big) + gap, text.hint, small, white);
    return out;
}

render::TargetRect cue_rect(const render::TargetRect& panel, VkExtent2D extent, std::uint32_t banner_width, std::uint32_t banner_height)
{
    const float w_px = float(std::max(extent.width, 1u)), h_px = float(std::max(extent.height, 1u));
    // the banner's own size, or less to fit 90 % of the panel's width
    const float width = std::min(float(banner_width) / w_px, 0.9f * panel.width);
    const float height = width * w_px * float(banner_height) / float(std::max(banner_width, 1u)) / h_px;
    return {panel.x + 0.5f * (panel.width - width), panel.y + 0.5f * (panel.height - height), width, height};
}

CuePass::CuePass(gpu::CommandPool& commands, VkFormat format)
    : nearest_(commands.context(), gpu::Filter::nearest), banner_pass_(commands.context(), format, {})
{
    for (ImageCue cue : {ImageCue::no_contact, ImageCue::outside_region, ImageCue::volume_pending}) {
        const io::RgbaImage drawn = cue_banner(cue);
        Banner& b = banners_[std::size_t(cue)];
        b.width = drawn.width;
        b.height = drawn.height;
        b.image = gpu::Image(commands.context(), VkExtent2D{drawn.width, drawn.height}, VK_FORMAT_R8G8B8A8_UNORM,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
        gpu::upload_image(commands, b.image, std::as_bytes(std::span(drawn.pixels)));
    }
}

void CuePass::set(ImageCue cue, const render::TargetRect& panel, VkExtent2D extent)
{
    cue_ = cue;
    if (cue == ImageCue::none) return;
    const Banner& b = banners_[std::size_t(cue)];
    banner_pass_.show(b.image, nearest_);
    banner_pass_.set_rect(cue_rect(panel, extent, b.width, b.height));
}

void CuePass::record(const gpu::PassContext& frame)
{
    // no cue: nothing drawn (the recorder's barrier before this pass costs nothing worth sparing)
    if (cue_ != ImageCue::none) banner_pass_.record(frame);
}

}  // namespace echosim::runner

#include "trainer/station_sheet_pass.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "exam/station_sheet.hpp"

namespace echosim::trainer {

exam::SheetStyle screen_sheet_style(int width, int height, float ui_scale)
{
    exam::SheetStyle s;
    s.width = width;
    s.max_height = height;
    s.thumb_width = 400;  // a station's image at its own size, at most
    s.gap = 12;
    s.caption_scale = std::max(1, int(std::lround(ui_scale)));
    // ImGui's dark window background (ui::solid_background) and text
    s.paper = {15, 15, 15, 255};
    s.ink = {230, 230, 230, 255};
    s.muted = {150, 150, 150, 255};
    s.placeholder = {40, 40, 40, 255};
    s.status_frames = true;
    return s;
}

StationSheetPass::StationSheetPass(gpu::CommandPool& commands, VkFormat format)
    : commands_(commands), nearest_(commands.context(), gpu::Filter::nearest), panel_(commands.context(), format, {})
{
}

void StationSheetPass::set(const exam::ExamReport& report, const std::filesystem::path& dir, const std::optional<ScreenState::Rect>& area,
                           VkExtent2D extent, float ui_scale)
{
    shown_ = false;
    if (!area || extent.width == 0 || extent.height == 0) return;
    const int w = int(std::floor(area->x1 - area->x0)), h = int(std::floor(area->y1 - area->y0));
    if (w < 16 || h < 16) return;
    const exam::SheetStyle style = screen_sheet_style(w, h, ui_scale);
    if (dir != made_dir_ || w != made_for_w_ || h != made_for_h_ || style.caption_scale != made_caption_scale_) {
        const io::RgbaImage sheet = exam::station_sheet(report, dir, style);
        made_dir_ = dir;
        made_for_w_ = w;
        made_for_h_ = h;
        made_caption_scale_ = style.caption_scale;
        made_width_ = sheet.width;
        made_height_ = sheet.height;
        commands_.context().wait_idle();  // the sheet it replaces may be in a frame still in flight
        sheet_ = {};
        if (sheet.width > 0 && sheet.height > 0) {
            sheet_ = gpu::Image(commands_.context(), VkExtent2D{sheet.width, sheet.height}, VK_FORMAT_R8G8B8A8_UNORM,
                                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
            gpu::upload_image(commands_, sheet_, std::as_bytes(std::span(sheet.pixels)));
        }
    }
    if (made_width_ == 0 || made_height_ == 0) return;
    // one texel a pixel, from the area's top left
    const float fw = float(extent.width), fh = float(extent.height);
    panel_.set_rect({std::round(area->x0) / fw, std::round(area->y0) / fh, float(made_width_) / fw, float(made_height_) / fh});
    panel_.show(sheet_, nearest_);
    shown_ = true;
}

void StationSheetPass::record(const gpu::PassContext& frame)
{
    if (shown_) panel_.record(frame);
}

}  // namespace echosim::trainer

// The report screen's images (issue 32: "the report screen, with what report.html holds"): the
// stations' images at their deepest press as one sheet of captioned thumbnails (exam/station_sheet),
// drawn into the area the report screen leaves for them (ScreenState::sheet_area), after the UI
// pass so it lies over the report window's background. Dear ImGui's Vulkan back-end in Debian
// (1.86) binds no texture of ours, so the sheet is a picture of its own, drawn by the image
// panel's pipeline at one texel a pixel.
//
// The sheet is made and uploaded when the report or the area's size changes (on the drawing
// thread, from the UI pass's draw callback, before the frame is recorded: the device is waited
// for first, so no frame in flight still reads the sheet it replaces).
#pragma once

#include <filesystem>
#include <optional>

#include "exam/exam_report.hpp"
#include "exam/station_sheet.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "render/image_panel_pass.hpp"
#include "trainer/trainer_screens.hpp"

namespace echosim::trainer {

class StationSheetPass final : public gpu::FramePass {
public:
    // `commands`: the drawing thread's pool (uploads go through it); `format`: the target's.
    StationSheetPass(gpu::CommandPool& commands, VkFormat format);

    // The frames from now on show `report`'s sheet (its images read from `dir`) at the top left of
    // `area` [px] in a frame of `extent`, its captions for a UI at `ui_scale`; no area: nothing.
    void set(const exam::ExamReport& report, const std::filesystem::path& dir, const std::optional<ScreenState::Rect>& area, VkExtent2D extent,
             float ui_scale = 1.0f);
    bool shown() const { return shown_; }
    std::uint32_t sheet_width() const { return made_width_; }
    std::uint32_t sheet_height() const { return made_height_; }

    const char* name() const override { return "station images"; }
    gpu::TargetUse target_use() const override { return panel_.target_use(); }
    void record(const gpu::PassContext& frame) override;

private:
    gpu::CommandPool& commands_;
    gpu::Sampler nearest_;
    render::ImagePanelPass panel_;
    gpu::Image sheet_;
    // what the sheet was made for: the report's folder and the area's size [px]
    std::filesystem::path made_dir_;
    int made_for_w_ = 0, made_for_h_ = 0, made_caption_scale_ = 0;
    std::uint32_t made_width_ = 0, made_height_ = 0;
    bool shown_ = false;
};

// The sheet's look on the report screen: light captions on the window's dark background (the
// bitmap font at the UI's scale, rounded), each thumbnail framed in its station's status colour,
// as large as `width` x `height` [px] allows.
exam::SheetStyle screen_sheet_style(int width, int height, float ui_scale = 1.0f);

}  // namespace echosim::trainer

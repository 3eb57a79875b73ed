// The image panel's cue (issue 31): where there is nothing to image, the panel says so instead of
// showing a black or meaningless slice, as a scanner shows nothing useful without coupling gel:
//   - NO CONTACT: the probe does not touch the skin (the session's echographic input has no
//     indentation profile: session/session.hpp's SessionView leaves EchoFrame::columns empty while
//     no tissue node is in contact with the probe, and before the first physics step);
//   - OUTSIDE THE MODELLED REGION: the image plane lies mostly outside the echographic volume (less
//     than half of a 5 x 5 grid of its pixel centres inside the volume's grid), so the slice would
//     show little but the volume's border: a probe slid off the exam region.
//   - IMAGES BEING MADE: the runner holds a stand-in while the case's volume is being made
//     (RunnerConfig::volume_pending: `echosim run`'s first window, app/trainer_window.hpp); it wins.
// The outside cue wins over no contact: off the volume the contact does not matter.
//
// The cue is drawn by CuePass, a frame pass after the image panel: a banner (text drawn on the CPU
// by io/bitmap_font, uploaded once at set-up) over the panel's middle, through the image panel's
// own pipeline (render/image_panel_pass.hpp), or nothing when there is no cue.
#pragma once

#include <array>

#include "echo/echo_frame.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "io/nrrd.hpp"
#include "io/png.hpp"
#include "render/image_panel_pass.hpp"
#include "render/target_rect.hpp"

namespace echosim::runner {

enum class ImageCue { none, no_contact, outside_region, volume_pending };

// The cue's two lines: the headline ("NO CONTACT", "OUTSIDE THE MODELLED REGION") and what to do.
struct CueText {
    const char* headline = "";
    const char* hint = "";
};
CueText cue_text(ImageCue cue);

// The cue for a frame's input on `plane`, the volume's geometry being `grid` (io::Volume, voxels
// not needed).
ImageCue image_cue(const echo::EchoFrame& frame, const echo::ImagePlane& plane, const io::Volume& grid);

// The banner of a cue (none: an empty image): its two lines, light on dark, sRGB-encoded bytes as
// the panel's images are.
io::RgbaImage cue_banner(ImageCue cue);

// Where the banner goes in a frame of `extent`: centred over `panel`, at most 90 % of its width,
// keeping the banner's aspect.
render::TargetRect cue_rect(const render::TargetRect& panel, VkExtent2D extent, std::uint32_t banner_width, std::uint32_t banner_height);

class CuePass final : public gpu::FramePass {
public:
    // `commands`: the calling thread's pool (the banners are uploaded now); `format`: the target's.
    CuePass(gpu::CommandPool& commands, VkFormat format);

    // The cue of the frames recorded from now on, over the image panel at `panel` in a frame of `extent`.
    void set(ImageCue cue, const render::TargetRect& panel, VkExtent2D extent);
    ImageCue cue() const { return cue_; }

    const char* name() const override { return "image cue"; }
    gpu::TargetUse target_use() const override { return banner_pass_.target_use(); }
    void record(const gpu::PassContext& frame) override;

private:
    struct Banner {
        gpu::Image image;
        std::uint32_t width = 0, height = 0;
    };
    std::array<Banner, 4> banners_;  // by ImageCue; none's is empty
    gpu::Sampler nearest_;           // the glyphs' pixels as drawn
    render::ImagePanelPass banner_pass_;
    ImageCue cue_ = ImageCue::none;
};

}  // namespace echosim::runner

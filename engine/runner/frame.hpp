// The frame a running simulator draws, in a window (`echosim run`) or offscreen (`soak`, `exam`),
// as one ordered list of passes (gpu/frame.hpp), so every configuration draws the same passes in
// the same order:
//
//   scene ─▶ [after_scene] ─▶ echographic image ─▶ [image] ─▶ image panel ─▶ image cue ─▶ [overlay]
//
//   - scene: the leg, the patch as the tissue leaves it, the probe (render/scene_pass.hpp), on the
//     left of the frame;
//   - echographic image: a compute pass running the image pipeline's stages (deform ▶ slice+post ▶
//     display copy, each declaring what it reads and writes: image/echo_image_gpu.hpp) from the
//     same physics step the scene shows (runner/echo_image_pass.hpp);
//   - image panel: that image on the right (render/image_panel_pass.hpp);
//   - image cue: NO CONTACT, OUTSIDE THE MODELLED REGION or IMAGES BEING MADE over the panel when there is nothing to
//     image (runner/image_cue.hpp).
// A configuration adds its own passes at the bracketed places (PassFactory): a B-mode pass filling
// the panel's image at `image`, a UI drawn over everything at `overlay`; a pass that follows the
// session (a SessionPass) is given each frame's view before the frame is drawn.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gpu/command_pool.hpp"
#include "gpu/context.hpp"
#include "gpu/frame.hpp"
#include "image/echo_image_gpu.hpp"
#include "io/nrrd.hpp"
#include "render/image_panel_pass.hpp"
#include "render/scene_pass.hpp"
#include "runner/default_scene.hpp"
#include "runner/echo_image_pass.hpp"
#include "runner/image_cue.hpp"

namespace echosim::runner {

// The echographic image's panel: the right of the frame, as tall as it is, keeping the image's
// aspect (at most half the width).
render::TargetRect echo_panel_rect(VkExtent2D frame, const echo::ImagePlane& plane);
// The 3-D scene's area: the frame left of that panel, its whole height.
render::TargetRect scene_rect(VkExtent2D frame, const echo::ImagePlane& plane);

// Where a configuration's own pass joins the frame (above).
enum class PassPlace { after_scene, image, overlay };

// What a configuration's pass is made with, once, when the frame is made.
struct PassSetup {
    const gpu::Context& ctx;
    gpu::CommandPool& commands;  // the drawing thread's
    VkFormat format;             // the presenter's target
    const DefaultScene& scene;
    // the image panel: a pass at PassPlace::image that makes the panel's image itself (a B-mode
    // pass) shows it there from its record(), after the echographic image pass has shown its own
    render::ImagePanelPass& panel;
    // the echographic image's pipeline: its plane() is the displayed image's (the depth control
    // changes it between frames)
    const image::EchoImageGpu& echo_image;
};

// A configuration's pass that follows the session: before each frame it is drawn, it gets the
// frame's view (the same physics step the scene and the image show) and the frame's extent.
class SessionPass : public gpu::FramePass {
public:
    virtual void set(const session::SessionView& state, VkExtent2D extent) = 0;
};
struct PassFactory {
    PassPlace place = PassPlace::overlay;
    std::function<std::unique_ptr<gpu::FramePass>(const PassSetup&)> make;
};

class SimulatorFrame {
public:
    // `ctx`, `commands` (this thread's pool) and `scene` must outlive the frame; `format` is the
    // presenter's. Uploads the volume (and its labels: null for none) once. Throws what the passes
    // throw (std::invalid_argument naming the pass of a list that cannot be recorded).
    SimulatorFrame(const gpu::Context& ctx, gpu::CommandPool& commands, VkFormat format, const DefaultScene& scene, const io::Volume& volume,
                   const io::Volume* labels, std::span<const PassFactory> extra = {},
                   echo::Imaging imaging = echo::Imaging::interpolative);
    SimulatorFrame(const SimulatorFrame&) = delete;
    SimulatorFrame& operator=(const SimulatorFrame&) = delete;

    // The next frames show `state` (taken once, so the scene and the image show one physics step)
    // in a frame of `extent`.
    void set(const DefaultScene& scene, const session::SessionView& state, VkExtent2D extent);
    const gpu::FramePasses& passes() const { return *passes_; }
    std::vector<std::string> pass_names() const;
    EchoImagePass& echo_pass() { return echo_pass_; }
    image::EchoImageGpu& echo_image() { return echo_image_; }
    // the cue the last set() chose
    ImageCue cue() const { return cue_pass_.cue(); }
    // The volume stands in for one being made (RunnerConfig::volume_pending): the cue says so.
    void set_volume_pending(bool pending) { volume_pending_ = pending; }

private:
    render::ScenePass scene_pass_;
    image::EchoImageGpu echo_image_;
    gpu::Sampler smooth_;
    render::ImagePanelPass panel_;
    EchoImagePass echo_pass_;
    CuePass cue_pass_;
    std::vector<std::unique_ptr<gpu::FramePass>> extra_;  // the configuration's
    std::vector<SessionPass*> following_;                 // those of them that follow the session
    std::vector<gpu::FramePass*> order_;
    std::optional<gpu::FramePasses> passes_;
    gpu::CommandPool& commands_;     // the drawing thread's, for the leg's uploads when the window moves
    int drawn_window_ = 0;            // the exam window the scene pass holds (Session::window_serial)
    bool volume_pending_ = false;
};

}  // namespace echosim::runner

// The frame every driver of a session draws, in a window (`echosim run`) or offscreen (`echosim
// soak`): the scene (the leg, the patch as the tissue leaves it, the probe) on the left and, on the
// right, the echographic image made on the GPU from the same physics step (its volume uploaded once). One
// object so the window and the headless drivers draw the same passes in the same order.
#pragma once

#include <memory>

#include "app/default_scene.hpp"
#include "app/echo_image_pass.hpp"
#include "app/volume_source.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/context.hpp"
#include "gpu/frame.hpp"
#include "image/echo_image_gpu.hpp"
#include "render/image_panel_pass.hpp"
#include "render/scene_pass.hpp"

namespace echosim::app {

// The echographic image's panel: the right of the frame, as tall as it is, keeping the image's
// aspect (at most half the width).
render::TargetRect echo_panel_rect(VkExtent2D frame, const echo::ImagePlane& plane);

class SessionFrame {
public:
    // `ctx`, `commands` (this thread's pool) and `scene` must outlive the frame; `format` is the
    // presenter's. Uploads the volume (and its labels) once.
    SessionFrame(const gpu::Context& ctx, gpu::CommandPool& commands, VkFormat format, const DefaultScene& scene, const VolumePair& volumes);
    SessionFrame(const SessionFrame&) = delete;
    SessionFrame& operator=(const SessionFrame&) = delete;

    // The next frames show `state` (taken once, so the scene and the image show one physics step)
    // in a frame of `extent`.
    void set(const DefaultScene& scene, const session::SessionView& state, VkExtent2D extent);
    const gpu::FramePasses& passes() const { return passes_; }
    EchoImagePass& echo_pass() { return echo_pass_; }

private:
    render::ScenePass scene_pass_;
    image::EchoImageGpu echo_image_;
    gpu::Sampler smooth_;
    render::ImagePanelPass panel_;
    EchoImagePass echo_pass_;
    gpu::FramePasses passes_;
};

}  // namespace echosim::app

// The live echographic image in the window's frame: a compute pass, recorded before the image
// panel, that runs the image pipeline (image/echo_image_gpu.hpp) for the frame's slot from the
// latest frame input and points the panel at the slot's image. The image never leaves the GPU.
#pragma once

#include "echo/echo_frame.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "image/echo_image_gpu.hpp"
#include "render/image_panel_pass.hpp"

namespace echosim::app {

class EchoImagePass final : public gpu::FramePass {
public:
    // `panel` must come after this pass in the frame's passes; all three must outlive the frames.
    EchoImagePass(image::EchoImageGpu& pipeline, render::ImagePanelPass& panel, const gpu::Sampler& sampler)
        : pipeline_(pipeline), panel_(panel), sampler_(sampler)
    {
    }

    // The input of the frames recorded from now on (copied: the session's changes every frame).
    void set_frame(const echo::EchoFrame& frame) { frame_ = frame; }

    const char* name() const override { return "echographic image"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::none(); }
    void record(const gpu::PassContext& frame) override
    {
        pipeline_.record(frame.cmd, frame.slot, frame_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        panel_.show(pipeline_.image(frame.slot), sampler_);
    }

private:
    image::EchoImageGpu& pipeline_;
    render::ImagePanelPass& panel_;
    const gpu::Sampler& sampler_;
    echo::EchoFrame frame_;
};

}  // namespace echosim::app

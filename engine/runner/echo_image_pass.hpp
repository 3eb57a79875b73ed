// The live echographic image in the window's frame: a compute pass, recorded before the image
// panel, that runs the image pipeline (image/echo_image_gpu.hpp) for the frame's slot from the
// latest frame input and points the panel at the slot's image. The image never leaves the GPU,
// unless read-back is enabled (the live link, `echosim run --igtl`): then each frame's image is
// also copied to the host in the same command buffer, and handed to the sink with the input it was
// made from once the GPU is done with it: when the slot is recorded again, after the presenter has
// waited for the slot's fence (gpu/frame.hpp), so nothing waits for it.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>

#include "echo/echo_frame.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "image/echo_image_gpu.hpp"
#include "render/image_panel_pass.hpp"

namespace echosim::runner {

class EchoImagePass final : public gpu::FramePass {
public:
    // A frame drawn and read back: its input, the plane it was drawn in (the depth may have changed
    // since), its displayed image (grey bytes, row-major), and the wall clock [s since the UNIX
    // epoch] when its input was set.
    using ReadbackSink = std::function<void(const echo::EchoFrame& frame, const echo::ImagePlane& plane, std::span<const std::uint8_t> grey,
                                            double wall_clock_s)>;

    // `panel` must come after this pass in the frame's passes; all three must outlive the frames.
    EchoImagePass(image::EchoImageGpu& pipeline, render::ImagePanelPass& panel, const gpu::Sampler& sampler)
        : pipeline_(pipeline), panel_(panel), sampler_(sampler)
    {
    }

    // From now on every frame is also read back and handed to `sink` (on the recording thread, from
    // inside a later frame's record()), a slot's worth of frames behind the display.
    void enable_readback(const gpu::Context& ctx, ReadbackSink sink)
    {
        pipeline_.enable_readback(ctx);
        sink_ = std::move(sink);
    }

    // The input of the frames recorded from now on (copied: the session's changes every frame);
    // ignored while frozen.
    void set_frame(const echo::EchoFrame& frame)
    {
        if (frozen_) return;
        frame_ = frame;
        if (sink_) wall_clock_s_ = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    }

    // Frozen, the frames show the input set last before (a scanner's freeze: the trainee studies
    // the image, measures on it, while the probe and the tissue go on).
    void set_frozen(bool frozen) { frozen_ = frozen; }
    bool frozen() const { return frozen_; }

    const char* name() const override { return "echographic image"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::none(); }
    void record(const gpu::PassContext& frame) override
    {
        Drawn& drawn = drawn_[std::size_t(frame.slot)];
        if (sink_ && drawn.valid) sink_(drawn.frame, drawn.plane, pipeline_.readback(frame.slot), drawn.wall_clock_s);
        pipeline_.record(frame.cmd, frame.slot, frame_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        panel_.show(pipeline_.image(frame.slot), sampler_);
        if (sink_) {
            drawn.frame = frame_;  // keeps its storage: no allocation per frame
            drawn.plane = pipeline_.plane();
            drawn.wall_clock_s = wall_clock_s_;
            drawn.valid = true;
        }
    }

private:
    // what a slot's last frame was drawn from
    struct Drawn {
        echo::EchoFrame frame;
        echo::ImagePlane plane;
        double wall_clock_s = 0;
        bool valid = false;
    };
    image::EchoImageGpu& pipeline_;
    render::ImagePanelPass& panel_;
    const gpu::Sampler& sampler_;
    echo::EchoFrame frame_;
    ReadbackSink sink_;
    double wall_clock_s_ = 0;
    bool frozen_ = false;
    std::array<Drawn, gpu::kFramesInFlight> drawn_;
};

}  // namespace echosim::runner

// A view of an image in a rectangle of the frame: where the echographic image will show beside the
// 3D scene. It loads the target (it draws over what the scene left) and covers its rectangle with
// the image, opaque, through the sampler given (nearest shows the pixels as they are, linear
// smooths an image smaller than its panel).
//
// The image: 2-D, 8-bit display values (sRGB-encoded grey levels, as PNGs and scanners have them;
// the target shows those very bytes) in a UNORM format, which the panel's shader decodes, or an
// sRGB one, which the sampler decodes (cheaper on lavapipe), in layout SHADER_READ_ONLY_OPTIMAL, its last write made
// visible to fragment shaders by whoever wrote it (upload_image does; a compute pass of the frame
// puts its own barrier after its dispatch).
//
// Frame slots: each slot has its own image binding, so the image pipeline can fill one slot's image
// while the other slot's frame is on screen. show() only notes what the next frames show; record()
// for slot s (called once the presenter has waited for slot s's previous frame) re-points slot s's
// binding when it shows something else, so a window loop may call show() at any frame. Nothing
// shown yet: the panel draws nothing.
//
// Lifetime: the destructor waits for the device before it destroys what frames in flight may use
// (gpu/frame.hpp).
#pragma once

#include <array>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/descriptors.hpp"
#include "gpu/frame.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "render/target_rect.hpp"

namespace echosim::render {

class ImagePanelPass final : public gpu::FramePass {
public:
    ImagePanelPass(const gpu::Context& ctx, VkFormat color_format, TargetRect rect);
    ~ImagePanelPass() override;
    ImagePanelPass(const ImagePanelPass&) = delete;
    ImagePanelPass& operator=(const ImagePanelPass&) = delete;

    void set_rect(const TargetRect& rect) { rect_ = rect; }
    const TargetRect& rect() const { return rect_; }
    // Shows `image` (2-D, else std::invalid_argument) through `sampler` in the frames recorded from
    // now on; both must outlive those frames. Any time, between frames or from a pass recorded
    // before the panel in the same frame: no GPU object is touched here.
    void show(const gpu::Image& image, const gpu::Sampler& sampler);

    const char* name() const override { return "image panel"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::color_attachment(gpu::TargetLoad::load); }
    void record(const gpu::PassContext& frame) override;

private:
    // what a slot's descriptor set points at (the handles, read when the slot is recorded, so an
    // image made anew in the same object is seen)
    struct Shown {
        VkImageView view = VK_NULL_HANDLE;
        VkSampler sampler = VK_NULL_HANDLE;
        bool operator==(const Shown&) const = default;
    };

    const gpu::Context& ctx_;
    VkFormat color_format_;
    TargetRect rect_;
    const gpu::Image* image_ = nullptr;  // what show() was last given
    const gpu::Sampler* sampler_ = nullptr;
    std::array<Shown, gpu::kFramesInFlight> bound_{};  // per slot
    gpu::SlotDescriptors descriptors_;
    gpu::Pipeline pipeline_;       // on descriptors_' layout: declared after it
    gpu::Pipeline srgb_pipeline_;  // for images of an sRGB format, which the sampler decodes
};

}  // namespace echosim::render

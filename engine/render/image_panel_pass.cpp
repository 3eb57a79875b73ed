#include "render/image_panel_pass.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "echosim_graphics_shaders.hpp"
#include "render/graphics_pipeline.hpp"
#include "gpu/vk_error.hpp"
#include "panel_bindings.h"

namespace echosim::render {
namespace {

constexpr gpu::BindingKind kBindings[] = {gpu::BindingKind::sampled_image};  // PANEL_IMAGE_BINDING
static_assert(PANEL_IMAGE_SET == 0 && PANEL_IMAGE_BINDING == 0, "the panel's one binding is binding 0 of set 0");

// The panel's pipeline: no vertex buffers (the vertex shader makes the quad's corners from their
// index), opaque (the panel replaces the scene under it); `sampler_decodes`: for sRGB images. The
// target's format says whether it encodes what the shader writes (shaders/panel.frag).
VkPipeline make_panel(const gpu::Context& ctx, VkPipelineLayout layout, VkFormat color_format, bool sampler_decodes)
{
    // SAMPLER_DECODES and TARGET_ENCODES, shaders/panel.frag
    const std::array<VkBool32, 2> constants{sampler_decodes ? VK_TRUE : VK_FALSE, gpu::is_srgb(color_format) ? VK_TRUE : VK_FALSE};
    GraphicsPipelineDesc desc;
    desc.name = "panel";
    desc.vertex_spirv = shaders::panel_vert;
    desc.fragment_spirv = shaders::panel_frag;
    desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    desc.color_format = color_format;
    desc.constants = constants;
    return create_graphics_pipeline(ctx.device(), layout, desc);
}

}  // namespace

ImagePanelPass::ImagePanelPass(const gpu::Context& ctx, VkFormat color_format, TargetRect rect)
    : ctx_(ctx), color_format_(color_format), rect_(rect), descriptors_(ctx, kBindings, VK_SHADER_STAGE_FRAGMENT_BIT, "image panel"),
      pipeline_(ctx.device(), descriptors_.layout(), {}, "panel", [&](VkPipelineLayout layout) { return make_panel(ctx, layout, color_format, false); }),
      srgb_pipeline_(ctx.device(), descriptors_.layout(), {}, "panel (sRGB image)",
                     [&](VkPipelineLayout layout) { return make_panel(ctx, layout, color_format, true); })
{
}

// frames in flight may still use the pipeline and the descriptor sets (gpu/frame.hpp,
// "Lifetime"); they go after this, with their members
ImagePanelPass::~ImagePanelPass() { ctx_.wait_idle(); }

void ImagePanelPass::show(const gpu::Image& image, const gpu::Sampler& sampler)
{
    if (image.type() != VK_IMAGE_TYPE_2D) throw std::invalid_argument("image panel: shows 2-D images only");
    image_ = &image;
    sampler_ = &sampler;
}

void ImagePanelPass::record(const gpu::PassContext& frame)
{
    const VkRect2D area = target_pixels(rect_, frame.target.extent);
    if (!image_ || area.extent.width == 0 || area.extent.height == 0) return;

    // the presenter has waited for this slot's previous frame: its set may be re-pointed now
    const Shown shown{image_->view(), sampler_->handle()};
    Shown& bound = bound_[std::size_t(frame.slot)];
    if (bound != shown) {
        const gpu::Binding binding = gpu::Binding::sampled(*image_, *sampler_);
        descriptors_.bind(frame.slot, std::span(&binding, 1));
        bound = shown;
    }

    begin_rendering_over(frame.cmd, frame.target.view, area, target_use().attachment_load_op());  // keep what the scene drew around the panel
    const gpu::Pipeline& pipeline = gpu::is_srgb(image_->format()) ? srgb_pipeline_ : pipeline_;
    vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.handle());
    const VkDescriptorSet set = descriptors_.set(frame.slot);
    vkCmdBindDescriptorSets(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), PANEL_IMAGE_SET, 1, &set, 0, nullptr);
    vkCmdDraw(frame.cmd, PANEL_VERTEX_COUNT, 1, 0, 0);
    vkCmdEndRendering(frame.cmd);
}

}  // namespace echosim::render

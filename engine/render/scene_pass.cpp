#include "render/scene_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "core/probe_spec.hpp"
#include "echosim_graphics_shaders.hpp"
#include "render/graphics_pipeline.hpp"
#include "gpu/vk_error.hpp"
#include "mesh_bindings.h"

namespace echosim::render {

using gpu::check;
using gpu::kFramesInFlight;
using gpu::MemoryUse;
using gpu::transition;
using gpu::upload_buffer;

namespace {

// sRGB's encoding of a linear value in 0..1 (shaders/srgb.glsl's linear_to_srgb)
float srgb_encode(float c)
{
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

using mesh_bindings::DrawPush;
using mesh_bindings::FrameUniforms;

constexpr gpu::BindingKind kBindings[] = {gpu::BindingKind::uniform_buffer};  // MESH_FRAME_BINDING
static_assert(MESH_FRAME_SET == 0 && MESH_FRAME_BINDING == 0, "the mesh's one binding is binding 0 of set 0");

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> s)
{
    return std::as_bytes(s);
}

}  // namespace

ScenePass::ScenePass(const gpu::Context& ctx, gpu::CommandPool& uploads, VkFormat color_format, const SceneMeshes& meshes)
    : ctx_(ctx), color_format_(color_format),
      descriptors_(ctx, kBindings, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, "scene"),
      vertex_lit_(ctx.device(), descriptors_.layout(), {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawPush)},
                  "mesh (lit per vertex)",
                  [&](VkPipelineLayout layout) { return create_mesh_pipeline(ctx.device(), layout, color_format, kDepthFormat, false); }),
      pixel_lit_(ctx.device(), descriptors_.layout(), {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawPush)},
                 "mesh (lit per pixel)",
                 [&](VkPipelineLayout layout) { return create_mesh_pipeline(ctx.device(), layout, color_format, kDepthFormat, true); }),
      probe_ghost_(ctx.device(), descriptors_.layout(), {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawPush)},
                   "mesh (the probe's ghost)",
                   [&](VkPipelineLayout layout) { return create_mesh_pipeline(ctx.device(), layout, color_format, kDepthFormat, true, true); })
{
    probe_.vertices = upload_buffer(uploads, bytes_of(std::span(meshes.probe.vertices)), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    probe_.indices = upload_buffer(uploads, bytes_of(std::span(meshes.probe.indices)), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    probe_.index_count = std::uint32_t(meshes.probe.indices.size());
    for (int i = 0; i < kFramesInFlight; ++i) {
        Slot& slot = slots_[std::size_t(i)];
        slot.uniforms = gpu::Buffer(ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::host_visible);
        // each slot's set points at its own uniforms for good: bound once, at set-up
        const gpu::Binding uniforms = gpu::Binding::uniform(slot.uniforms);
        descriptors_.bind(i, std::span(&uniforms, 1));
    }
    upload_leg(uploads, meshes.static_mesh, meshes.patch_rest);
}

void ScenePass::upload_leg(gpu::CommandPool& uploads, const scene::Mesh& static_mesh, const scene::Mesh& patch_rest)
{
    // static geometry goes to device-local memory once per leg
    static_mesh_.vertices = upload_buffer(uploads, bytes_of(std::span(static_mesh.vertices)), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    static_mesh_.indices = upload_buffer(uploads, bytes_of(std::span(static_mesh.indices)), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    static_mesh_.index_count = std::uint32_t(static_mesh.indices.size());
    patch_indices_ = upload_buffer(uploads, bytes_of(std::span(patch_rest.indices)), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    patch_index_count_ = std::uint32_t(patch_rest.indices.size());
    patch_vertex_count_ = patch_rest.vertices.size();
    for (Slot& slot : slots_) {
        slot.patch_vertices = gpu::Buffer(ctx_, std::max<VkDeviceSize>(1, patch_vertex_count_ * sizeof(scene::Vertex)),
                                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryUse::host_visible);
        slot.patch_vertices.write(bytes_of(std::span(patch_rest.vertices)));
    }
    view_.patch_vertices = {};  // a view of the old patch is not drawn on the new one
}

void ScenePass::replace_leg(gpu::CommandPool& uploads, const scene::Mesh& static_mesh, const scene::Mesh& patch_rest)
{
    // frames in flight still draw the buffers about to be replaced (gpu/frame.hpp, "Lifetime")
    ctx_.wait_idle();
    upload_leg(uploads, static_mesh, patch_rest);
}

// frames in flight may still use the pipeline, the descriptor sets and the slots' buffers
// (gpu/frame.hpp, "Lifetime"); the members go after this
ScenePass::~ScenePass() { ctx_.wait_idle(); }

VkPipeline ScenePass::create_mesh_pipeline(VkDevice dev, VkPipelineLayout layout, VkFormat color_format, VkFormat depth_format,
                                           bool lit_per_pixel, bool ghost)
{
    // LIT_PER_PIXEL and TARGET_ENCODES, shaders/mesh_lighting.glsl
    const std::array<VkBool32, 2> constants{lit_per_pixel ? VK_TRUE : VK_FALSE, gpu::is_srgb(color_format) ? VK_TRUE : VK_FALSE};
    const VkVertexInputBindingDescription vertex_binding{0, sizeof(scene::Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(scene::Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(scene::Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(scene::Vertex, color)},
    };
    GraphicsPipelineDesc desc;
    desc.name = "mesh";
    desc.vertex_spirv = shaders::mesh_vert;
    desc.fragment_spirv = shaders::mesh_frag;
    desc.vertex_bindings = std::span(&vertex_binding, 1);
    desc.vertex_attributes = attributes;
    // meshes wind counter-clockwise seen from outside (scene::orient_to_normals); Vulkan's y-down
    // framebuffer and our y-flipped projection cancel, so front faces stay counter-clockwise
    desc.cull = VK_CULL_MODE_BACK_BIT;
    desc.front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    desc.color_format = color_format;
    desc.depth_format = depth_format;
    desc.constants = constants;
    desc.blend = ghost;
    desc.behind = ghost;
    return create_graphics_pipeline(dev, layout, desc);
}

namespace {

glm::mat4 gel_from_world(const FrameView& view)
{
    // no probe, no gel: every point maps outside the ellipse
    if (!view.show_probe) return glm::mat4(glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(10.0f, 0.0f, 10.0f, 1.0f));
    // the gel spreads 10 mm past the face's ends and 12 mm either side of it (kLinearProbe: a 40 x
    // 10 mm face): what a probe slid in gel leaves on the skin
    const glm::vec3 semi_axes(float(kLinearProbe.face_width_mm / 2 + 10.0), 1.0f, float(kLinearProbe.face_thickness_mm / 2 + 12.0));
    return glm::scale(glm::mat4(1.0f), 1.0f / semi_axes) * glm::inverse(view.probe_to_world);
}

}  // namespace

void ScenePass::draw(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, VkBuffer vertices, VkBuffer indices, std::uint32_t index_count,
                     const glm::mat4& model, const glm::vec4& tint, bool gel, float opacity)
{
    const DrawPush push{model, tint, glm::vec4(gel ? 1.0f : 0.0f, opacity, 0.0f, 0.0f)};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.handle());
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
}

void ScenePass::set_view(const FrameView& view)
{
    if (view.patch_vertices.size() != patch_vertex_count_)
        throw std::invalid_argument("scene pass: patch has " + std::to_string(view.patch_vertices.size()) +
                                    " vertices, the pass was built for " + std::to_string(patch_vertex_count_));
    view_ = view;
}

void ScenePass::record(const gpu::PassContext& pass)
{
    const VkCommandBuffer cmd = pass.cmd;
    const gpu::FrameTarget& target = pass.target;
    const FrameView& view = view_;
    Slot& slot = slots_[std::size_t(pass.slot)];
    if (slot.depth.extent().width != target.extent.width || slot.depth.extent().height != target.extent.height)
        slot.depth = gpu::Image(ctx_, target.extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                VK_IMAGE_ASPECT_DEPTH_BIT);

    const VkRect2D area = target_pixels(area_, target.extent);

    // per-frame data: the slot's fence has signalled, so the GPU no longer reads these buffers
    const float aspect = float(std::max(1u, area.extent.width)) / float(std::max(1u, area.extent.height));
    FrameUniforms frame{};
    frame.view_proj = view.camera.projection(aspect) * view.camera.view();
    frame.eye = glm::vec4(view.camera.eye(), 1.0f);
    // an examination-room key light from above the patient's left shoulder, a cool fill from the
    // other side, and dim ambient; the colours are linear, so these are modest numbers
    frame.key_dir = glm::vec4(glm::normalize(glm::vec3(-0.45f, 0.80f, -0.40f)), 0.85f);
    frame.fill_dir = glm::vec4(glm::normalize(glm::vec3(0.6f, 0.4f, 0.6f)), 0.25f);
    frame.sky = glm::vec4(0.16f, 0.17f, 0.20f, 1.0f);
    frame.ground = glm::vec4(0.04f, 0.035f, 0.035f, 1.0f);
    frame.gel_from_world = gel_from_world(view);
    slot.uniforms.write(std::as_bytes(std::span(&frame, 1)));
    // no view set yet: the patch keeps the rest shape it was made with
    if (!view.patch_vertices.empty()) slot.patch_vertices.write(std::as_bytes(view.patch_vertices));

    // the target is already a colour attachment (the frame recorder put it there); the depth
    // buffer is the pass's own
    transition(cmd, slot.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);

    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = target_use().attachment_load_op();
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    // the background, linear; a target that does not encode takes it encoded, as the shaders write
    const glm::vec3 background(0.012f, 0.014f, 0.018f);
    const glm::vec3 clear = gpu::is_srgb(color_format_)
                                ? background
                                : glm::vec3(srgb_encode(background.r), srgb_encode(background.g), srgb_encode(background.b));
    color.clearValue.color = {{clear.r, clear.g, clear.b, 1.0f}};
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = slot.depth.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, target.extent};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);  // clears all the target: what no pass draws is background
    if (area.extent.width == 0 || area.extent.height == 0) {
        vkCmdEndRendering(cmd);
        return;
    }

    const VkViewport vp{float(area.offset.x), float(area.offset.y), float(area.extent.width), float(area.extent.height), 0.0f, 1.0f};
    const VkRect2D scissor = area;
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    // the two pipelines' layouts are made from the same set layout and push range, so the set
    // bound on one stays bound across the switch
    const VkDescriptorSet set = descriptors_.set(pass.slot);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, vertex_lit_.layout(), MESH_FRAME_SET, 1, &set, 0, nullptr);

    const glm::mat4 identity(1.0f);
    // the matte skin, drape and table first: they hide most of what lies behind them
    draw(cmd, vertex_lit_, static_mesh_.vertices.handle(), static_mesh_.indices.handle(), static_mesh_.index_count, identity,
         glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
    // the patch carries ultrasound gel: same skin, a little glossier
    draw(cmd, pixel_lit_, slot.patch_vertices.handle(), patch_indices_.handle(), patch_index_count_, identity,
         glm::vec4(1.0f, 1.0f, 1.0f, 0.35f), true);
    if (view.show_probe) {
        draw(cmd, pixel_lit_, probe_.vertices.handle(), probe_.indices.handle(), probe_.index_count, view.probe_to_world,
             glm::vec4(1.0f, 1.0f, 1.0f, 0.55f));
        // where the leg or the table hides it, the probe seen through them: a trainee at the
        // popliteal fossa (under the knee, on the table) still sees where the probe is
        draw(cmd, probe_ghost_, probe_.vertices.handle(), probe_.indices.handle(), probe_.index_count, view.probe_to_world,
             glm::vec4(1.0f, 1.0f, 1.0f, 0.55f), false, kProbeGhostOpacity);
    }
    vkCmdEndRendering(cmd);
}

}  // namespace echosim::render

// The scene pass: draws the static leg (uploaded once), the exam patch (vertices replaced every
// frame) and the probe into its area of the frame's target (all of it unless told), with a depth
// buffer of its own. It clears the whole target, so it comes first among the passes that draw
// (gpu/frame.hpp); views and overlays load what it leaves. Presenters own the targets and the
// frame pacing; the pass only records.
//
// The leg changes shape when the exam window moves (session/session.hpp, "The exam window": the
// static mesh's hole goes where the patch goes, and the patch has as many vertices as the window's
// cells need): replace_leg uploads both again. Rare (a lifted probe's move), never per frame.
//
// Frame slots: per slot the pass keeps its own uniform buffer (and descriptor set pointing at it),
// patch vertex buffer and depth image (the presenter guarantees the GPU is done with a slot before
// it is recorded again).
//
// Lifetime: the destructor waits for the device before it destroys what frames in flight may use
// (gpu/frame.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "gpu/command_pool.hpp"
#include "gpu/context.hpp"
#include "gpu/descriptors.hpp"
#include "gpu/frame.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "render/target_rect.hpp"
#include "scene/camera.hpp"
#include "scene/mesh.hpp"

namespace echosim::render {

// What changes from frame to frame.
struct FrameView {
    scene::OrbitCamera camera;
    std::span<const scene::Vertex> patch_vertices;  // as many as the patch's rest mesh
    glm::mat4 probe_to_world{1.0f};
    bool show_probe = true;
};

struct SceneMeshes {
    const scene::Mesh& static_mesh;
    const scene::Mesh& patch_rest;
    const scene::Mesh& probe;
};

class ScenePass final : public gpu::FramePass {
public:
    // Uploads the static meshes through `uploads` (the calling thread's pool) and waits for them.
    ScenePass(const gpu::Context& ctx, gpu::CommandPool& uploads, VkFormat color_format, const SceneMeshes& meshes);
    ~ScenePass() override;
    ScenePass(const ScenePass&) = delete;
    ScenePass& operator=(const ScenePass&) = delete;

    VkFormat color_format() const { return color_format_; }
    // What the next frame shows; its patch must have as many vertices as the rest mesh (checked
    // here) and stay valid until that frame is recorded.
    void set_view(const FrameView& view);
    // The static mesh and the patch of a leg whose exam window moved (session::Session::window_serial
    // changed), from the next frame recorded. Waits for the frames in flight (they draw the old
    // buffers: gpu/frame.hpp, "Lifetime"), then uploads through `uploads` (the calling thread's pool)
    // and waits for that; the next set_view's patch must have as many vertices as `patch_rest`.
    void replace_leg(gpu::CommandPool& uploads, const scene::Mesh& static_mesh, const scene::Mesh& patch_rest);
    // Where on the target the scene is drawn, from the next frame recorded: beside a panel rather
    // than under it, so the camera frames the leg in the space the trainee sees, and no pixel is
    // shaded to be painted over. The camera's aspect is the area's.
    void set_area(const TargetRect& area) { area_ = area; }

    const char* name() const override { return "scene"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::color_attachment(gpu::TargetLoad::clear); }
    void record(const gpu::PassContext& frame) override;

private:
    struct GpuMesh {
        gpu::Buffer vertices;
        gpu::Buffer indices;
        std::uint32_t index_count = 0;
    };
    struct Slot {
        gpu::Buffer uniforms;
        gpu::Buffer patch_vertices;
        gpu::Image depth;
    };

    void upload_leg(gpu::CommandPool& uploads, const scene::Mesh& static_mesh, const scene::Mesh& patch_rest);
    // `ghost`: the see-through pipeline that draws what lies behind what is drawn (blended, no depth
    // written), for the probe's ghost
    static VkPipeline create_mesh_pipeline(VkDevice device, VkPipelineLayout layout, VkFormat color_format, VkFormat depth_format,
                                           bool lit_per_pixel, bool ghost = false);
    void draw(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, VkBuffer vertices, VkBuffer indices, std::uint32_t index_count,
              const glm::mat4& model, const glm::vec4& tint, bool gel = false, float opacity = 0.0f);

    const gpu::Context& ctx_;
    VkFormat color_format_;
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    gpu::SlotDescriptors descriptors_;  // per slot: the slot's uniforms
    // on descriptors_' layout, declared after it: the one lights the dense matte meshes per
    // vertex, the other the glossy ones per pixel (shaders/mesh_lighting.glsl)
    gpu::Pipeline vertex_lit_, pixel_lit_;
    // the probe where the leg or the table hides it (the popliteal fossa's probe lies under the
    // knee), drawn see-through over what hides it at kProbeGhostOpacity
    gpu::Pipeline probe_ghost_;
    static constexpr float kProbeGhostOpacity = 0.45f;
    GpuMesh static_mesh_, probe_;
    gpu::Buffer patch_indices_;
    std::uint32_t patch_index_count_ = 0;
    std::size_t patch_vertex_count_ = 0;
    std::array<Slot, gpu::kFramesInFlight> slots_;
    FrameView view_;
    TargetRect area_;
};

}  // namespace echosim::render

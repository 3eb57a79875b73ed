// The scene renderer: draws the static leg (uploaded once), the exam patch (vertices replaced every
// frame) and the probe into any colour target, with a depth buffer of its own. Presenters own the
// targets (offscreen images, swapchain images) and the frame pacing; the renderer only records.
//
// Frame slots: up to kFramesInFlight frames may be in flight; per slot the renderer keeps its own
// uniform buffer, patch vertex buffer and depth image. The caller guarantees that the GPU is done
// with a slot (its fence signalled) before recording into it again.
#pragma once

#include <array>
#include <span>

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "scene/camera.hpp"
#include "scene/mesh.hpp"

namespace echosim::gpu {

inline constexpr int kFramesInFlight = 2;

struct RenderTarget {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkExtent2D extent{};
    // layout, stage and access the image is left in for whoever uses it next (present, copy)
    VkImageLayout final_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkPipelineStageFlags2 next_stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 next_access = VK_ACCESS_2_NONE;
};

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

class Renderer {
public:
    Renderer(const Context& ctx, VkFormat color_format, const SceneMeshes& meshes);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    VkFormat color_format() const { return color_format_; }
    void record(VkCommandBuffer cmd, int slot, const RenderTarget& target, const FrameView& view);

private:
    struct GpuMesh {
        Buffer vertices;
        Buffer indices;
        std::uint32_t index_count = 0;
    };
    struct Slot {
        Buffer uniforms;
        Buffer patch_vertices;
        Image depth;
        VkDescriptorSet descriptors = VK_NULL_HANDLE;
    };

    void create_pipeline();
    void destroy();  // releases the raw handles; members with destructors release themselves
    void draw(VkCommandBuffer cmd, VkBuffer vertices, VkBuffer indices, std::uint32_t index_count,
              const glm::mat4& model, const glm::vec4& tint);

    const Context& ctx_;
    VkFormat color_format_;
    VkFormat depth_format_ = VK_FORMAT_D32_SFLOAT;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    GpuMesh static_mesh_, probe_;
    Buffer patch_indices_;
    std::uint32_t patch_index_count_ = 0;
    std::size_t patch_vertex_count_ = 0;
    std::array<Slot, kFramesInFlight> slots_;
};

// Creates a shader module from embedded SPIR-V; throws with the shader's name on failure.
VkShaderModule create_shader_module(VkDevice device, std::span<const std::uint32_t> spirv, const char* name);

}  // namespace echosim::gpu

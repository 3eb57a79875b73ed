// The render layer's graphics pipelines, made one way: dynamic rendering into one colour attachment
// (and a depth attachment where the pass has one), viewport and scissor set when recording, filled
// polygons, opaque unless asked to blend. A pass says only what differs.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

namespace echosim::render {

struct GraphicsPipelineDesc {
    const char* name = "";  // for error messages, e.g. "mesh"
    std::span<const std::uint32_t> vertex_spirv, fragment_spirv;
    std::span<const VkVertexInputBindingDescription> vertex_bindings;  // empty: the shader makes its vertices
    std::span<const VkVertexInputAttributeDescription> vertex_attributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkFormat color_format = VK_FORMAT_UNDEFINED;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;  // UNDEFINED: no depth attachment, no depth test
    bool blend = false;  // "over" by the fragment's alpha (see-through overlays), else opaque
    // the depth test passes only behind what is drawn already (GREATER), and writes no depth: what
    // lies hidden is drawn over what hides it (with blend: seen through it)
    bool behind = false;
    // both shaders' boolean specialization constants, constant_id 0, 1, ... in order (a constant a
    // stage does not declare is ignored there)
    std::span<const VkBool32> constants;
};

// Throws std::runtime_error naming the pipeline when a shader module or the pipeline cannot be made.
VkPipeline create_graphics_pipeline(VkDevice device, VkPipelineLayout layout, const GraphicsPipelineDesc& desc);

}  // namespace echosim::render

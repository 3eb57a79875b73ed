// Shader modules from the SPIR-V that cmake/Shaders.cmake embeds in the binary; used by the compute
// kernels here and by the graphics passes of the render layer.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

// Creates a shader module from embedded SPIR-V; throws with the shader's name on failure.
VkShaderModule create_shader_module(VkDevice device, std::span<const std::uint32_t> spirv, const char* name);

}  // namespace echosim::gpu

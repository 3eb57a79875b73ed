#include "gpu/shader.hpp"

#include <string>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {

VkShaderModule create_shader_module(VkDevice device, std::span<const std::uint32_t> spirv, const char* name)
{
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device, &info, nullptr, &module), (std::string("vkCreateShaderModule ") + name).c_str());
    return module;
}

}  // namespace echosim::gpu

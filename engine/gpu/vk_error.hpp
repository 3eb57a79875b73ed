// Vulkan set-up errors as exceptions that carry the VkResult and what was being done, so a failure
// on a user's machine names its cause (vk-bootstrap's habit). Hot paths never throw through here:
// they return the VkResult and let the caller recover (a lost swapchain is recreated, not fatal).
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

const char* to_string(VkResult result);

class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& what)
        : std::runtime_error(what + " failed: " + to_string(result)), result_(result) {}
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

inline void check(VkResult result, const char* what)
{
    if (result != VK_SUCCESS) throw VulkanError(result, what);
}

}  // namespace echosim::gpu

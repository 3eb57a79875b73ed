// Which Vulkan physical device echosim runs on. Kept apart from the Context so the rule can be
// unit-tested without a GPU: a discrete GPU first, then an integrated one, then a virtual one, then
// a CPU implementation (Mesa lavapipe, what CI has). A name forced by `--gpu NAME` or ECHOSIM_GPU
// overrides the ranking; "cpu", "lavapipe" and "llvmpipe" all mean the CPU implementation.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

struct PhysicalDeviceInfo {
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::uint32_t api_version = 0;
    bool has_graphics_compute_queue = false;
    bool can_present = true;  // only asked when a window needs it
};

// Index of the device to use. Throws std::runtime_error listing the devices seen when none fits
// or when the forced name matches none.
std::size_t select_physical_device(const std::vector<PhysicalDeviceInfo>& devices, std::string_view forced_name);

const char* device_type_name(VkPhysicalDeviceType type);

}  // namespace echosim::gpu

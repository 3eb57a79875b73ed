#include "gpu/device_selection.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace echosim::gpu {
namespace {

constexpr std::uint32_t kRequiredApi = VK_API_VERSION_1_3;

std::string lower(std::string_view s)
{
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

int rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

std::string why_unusable(const PhysicalDeviceInfo& d)
{
    if (d.api_version < kRequiredApi) return "needs Vulkan 1.3";
    if (!d.has_graphics_compute_queue) return "no graphics+compute queue";
    if (!d.can_present) return "cannot present to this window system";
    return {};
}

bool matches(const PhysicalDeviceInfo& d, const std::string& wanted)
{
    if (wanted == "cpu" || wanted == "lavapipe" || wanted == "llvmpipe") return d.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    if (wanted == "discrete") return d.type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    if (wanted == "integrated") return d.type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
    return lower(d.name).find(wanted) != std::string::npos;
}

std::string describe(const std::vector<PhysicalDeviceInfo>& devices)
{
    if (devices.empty()) return " (no Vulkan device found: is mesa-vulkan-drivers installed?)";
    std::string out;
    for (const auto& d : devices) {
        out += "\n  - " + d.name + " [" + device_type_name(d.type) + "]";
        if (auto why = why_unusable(d); !why.empty()) out += " unusable: " + why;
    }
    return out;
}

}  // namespace

const char* device_type_name(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

std::size_t select_physical_device(const std::vector<PhysicalDeviceInfo>& devices, std::string_view forced_name)
{
    const std::string wanted = lower(forced_name);
    std::size_t best = devices.size();
    for (std::size_t i = 0; i < devices.size(); ++i) {
        const auto& d = devices[i];
        if (!why_unusable(d).empty()) continue;
        if (!wanted.empty() && !matches(d, wanted)) continue;
        if (best == devices.size() || rank(d.type) > rank(devices[best].type)) best = i;
    }
    if (best != devices.size()) return best;
    if (!wanted.empty())
        throw std::runtime_error("no usable Vulkan device matches --gpu/ECHOSIM_GPU '" + std::string(forced_name) +
                                 "'; devices seen:" + describe(devices));
    throw std::runtime_error("no usable Vulkan device; devices seen:" + describe(devices));
}

}  // namespace echosim::gpu

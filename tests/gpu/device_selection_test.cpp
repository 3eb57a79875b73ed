#include "gpu/device_selection.hpp"

#include <gtest/gtest.h>

namespace echosim::gpu {
namespace {

PhysicalDeviceInfo device(const char* name, VkPhysicalDeviceType type)
{
    return {name, type, VK_API_VERSION_1_3, true, true};
}

TEST(DeviceSelection, PrefersDiscreteThenIntegratedThenCpu)
{
    const std::vector<PhysicalDeviceInfo> all = {device("llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU),
                                                 device("Intel(R) UHD 770", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
                                                 device("NVIDIA H100", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU)};
    EXPECT_EQ(select_physical_device(all, ""), 2u);
    EXPECT_EQ(select_physical_device({all[0], all[1]}, ""), 1u);
    EXPECT_EQ(select_physical_device({all[0]}, ""), 0u);
}

TEST(DeviceSelection, ForcedNameWins)
{
    const std::vector<PhysicalDeviceInfo> all = {device("llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU),
                                                 device("NVIDIA H100", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU)};
    EXPECT_EQ(select_physical_device(all, "lavapipe"), 0u);
    EXPECT_EQ(select_physical_device(all, "CPU"), 0u);
    EXPECT_EQ(select_physical_device(all, "h100"), 1u);
    EXPECT_EQ(select_physical_device(all, "discrete"), 1u);
}

TEST(DeviceSelection, SkipsUnusableDevices)
{
    auto old = device("Old GPU", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    old.api_version = VK_API_VERSION_1_1;
    auto headless = device("Compute only", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    headless.can_present = false;
    const std::vector<PhysicalDeviceInfo> all = {old, headless, device("llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU)};
    EXPECT_EQ(select_physical_device(all, ""), 2u);
}

TEST(DeviceSelection, ErrorListsWhatWasSeen)
{
    const std::vector<PhysicalDeviceInfo> all = {device("llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU)};
    try {
        select_physical_device(all, "radeon");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("'radeon'"), std::string::npos) << m;
        EXPECT_NE(m.find("llvmpipe (LLVM 15) [cpu]"), std::string::npos) << m;
    }
    EXPECT_THROW(select_physical_device({}, ""), std::runtime_error);
}

}  // namespace
}  // namespace echosim::gpu

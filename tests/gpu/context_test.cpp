#include "gpu/context.hpp"

#include <cstring>

#include <gtest/gtest.h>

#include "gpu/resources.hpp"
#include "test_gpu.hpp"

namespace echosim::gpu {
namespace {

TEST(Context, StartsOnLavapipeWithValidationAndStaysSilent)
{
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        EXPECT_TRUE(ctx.validation_enabled());
        EXPECT_EQ(ctx.device_type(), VK_PHYSICAL_DEVICE_TYPE_CPU);
        // a buffer round trip through the GPU: upload, copy back, compare
        std::vector<std::uint32_t> data(1000);
        for (std::uint32_t i = 0; i < data.size(); ++i) data[i] = i * 2654435761u;
        CommandPool pool(ctx);
        Buffer device = upload_buffer(pool, std::as_bytes(std::span(data)), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        Buffer back(ctx, device.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::host_visible);
        pool.submit_and_wait([&](VkCommandBuffer cmd) {
            VkBufferCopy region{0, 0, device.size()};
            vkCmdCopyBuffer(cmd, device.handle(), back.handle(), 1, &region);
        });
        EXPECT_EQ(std::memcmp(back.mapped(), data.data(), device.size()), 0);
    }
    EXPECT_EQ(messages->load(), 0u);
}

TEST(Context, UnknownGpuNameFailsWithTheDevicesSeen)
{
    ContextOptions o = test::lavapipe_options();
    o.gpu = "no-such-gpu-xyz";
    try {
        Context ctx(o);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("llvmpipe"), std::string::npos) << e.what();
    }
}

TEST(Context, ValidationCatchesMisuse)
{
    // the layer is really listening: a buffer of size 0 is invalid usage
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = 0;
        info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        VkBuffer buffer = VK_NULL_HANDLE;
        testing::internal::CaptureStderr();
        if (vkCreateBuffer(ctx.device(), &info, nullptr, &buffer) == VK_SUCCESS) vkDestroyBuffer(ctx.device(), buffer, nullptr);
        const std::string printed = testing::internal::GetCapturedStderr();
        EXPECT_NE(printed.find("vulkan validation"), std::string::npos);
    }
    EXPECT_GT(messages->load(), 0u);
}

TEST(Context, ValidationReportsObjectsLeftWhenTheDeviceGoes)
{
    // why every GPU test reads the count after its context is gone: leaks are reported only then
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    std::uint32_t while_alive = 0;
    testing::internal::CaptureStderr();
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        VkSampler leaked = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateSampler(ctx.device(), &info, nullptr, &leaked), VK_SUCCESS);
        while_alive = ctx.validation_messages();
    }
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(while_alive, 0u);
    EXPECT_GT(messages->load(), 0u) << printed;
}

}  // namespace
}  // namespace echosim::gpu

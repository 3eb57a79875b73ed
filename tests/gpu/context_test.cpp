#include "gpu/context.hpp"

#include <chrono>
#include <cstring>
#include <thread>

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

TEST(Context, ThreadsWithTheirOwnPoolsSubmitAtTheSameTime)
{
    // two recording threads, each with its own command pool, submit small jobs at once while a
    // third waits for the device now and then: the queue is the context's to guard (the layer's
    // thread-safety checks report a queue used from two threads unsynchronised)
    constexpr int kJobs = 300;
    constexpr VkDeviceSize kWords = 64;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    int wrong[2] = {0, 0};
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        std::atomic<bool> done{false};
        const auto worker = [&](int thread) {
            CommandPool pool(ctx);
            Buffer device(ctx, kWords * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          MemoryUse::device_local);
            Buffer back(ctx, kWords * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::host_visible);
            for (int job = 0; job < kJobs; ++job) {
                const std::uint32_t value = std::uint32_t(thread) << 16 | std::uint32_t(job);
                // fill on the GPU, copy back, read: each job's own value in every word
                pool.submit_and_wait([&](VkCommandBuffer cmd) {
                    vkCmdFillBuffer(cmd, device.handle(), 0, VK_WHOLE_SIZE, value);
                    const VkMemoryBarrier2 fill_to_copy{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                        VK_ACCESS_2_TRANSFER_READ_BIT};
                    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
                    dependency.memoryBarrierCount = 1;
                    dependency.pMemoryBarriers = &fill_to_copy;
                    vkCmdPipelineBarrier2(cmd, &dependency);
                    const VkBufferCopy region{0, 0, kWords * 4};
                    vkCmdCopyBuffer(cmd, device.handle(), back.handle(), 1, &region);
                    host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
                });
                const auto* words = static_cast<const std::uint32_t*>(back.mapped());
                for (VkDeviceSize i = 0; i < kWords; ++i) wrong[thread] += words[i] != value;
            }
        };
        std::thread waiter([&] {
            while (!done.load()) {
                ctx.wait_idle();
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
        });
        std::thread a(worker, 0), b(worker, 1);
        a.join();
        b.join();
        done = true;
        waiter.join();
    }
    EXPECT_EQ(wrong[0], 0);
    EXPECT_EQ(wrong[1], 0);
    EXPECT_EQ(messages->load(), 0u);
}

}  // namespace
}  // namespace echosim::gpu

// The frame recorder: passes in order, each given the target in the layout it declared, the frame
// slot and the command buffer; the list refuses what cannot work. Offscreen on lavapipe with
// validation on (which checks every layout a command expects); the count is read after the
// device is gone.
#include "gpu/frame.hpp"

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/offscreen.hpp"
#include "test_gpu.hpp"

namespace echosim::gpu {
namespace {

constexpr VkExtent2D kExtent{64, 48};
constexpr VkRect2D kRect{{10, 20}, {30, 12}};  // the overlay's rectangle [px]

// Fills the whole target with red by a transfer clear (layout TRANSFER_DST_OPTIMAL).
struct TransferClearPass final : FramePass {
    const char* name() const override { return "transfer clear"; }
    TargetUse target_use() const override
    {
        return {{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT}, TargetLoad::clear};
    }
    void record(const PassContext& frame) override
    {
        const VkClearColorValue red{{1.0f, 0.0f, 0.0f, 1.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(frame.cmd, frame.target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &red, 1, &all);
    }
};

// Draws a blue rectangle over what the passes before left (a colour attachment, loaded).
struct OverlayPass final : FramePass {
    const char* name() const override { return "overlay"; }
    TargetUse target_use() const override { return TargetUse::color_attachment(TargetLoad::load); }
    void record(const PassContext& frame) override
    {
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = frame.target.view;
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = target_use().attachment_load_op();
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
        rendering.renderArea = {{0, 0}, frame.target.extent};
        rendering.layerCount = 1;
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachments = &color;
        vkCmdBeginRendering(frame.cmd, &rendering);
        VkClearAttachment blue{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
        blue.clearValue.color = {{0.0f, 0.0f, 1.0f, 1.0f}};
        const VkClearRect rect{kRect, 0, 1};
        vkCmdClearAttachments(frame.cmd, 1, &blue, 1, &rect);
        vkCmdEndRendering(frame.cmd);
    }
};

// Touches no target: notes the slots and command buffers it was given (a compute pass's place).
struct WitnessPass final : FramePass {
    std::vector<int> slots;
    std::vector<VkCommandBuffer> buffers;
    const char* name() const override { return "witness"; }
    TargetUse target_use() const override { return TargetUse::none(); }
    void record(const PassContext& frame) override
    {
        slots.push_back(frame.slot);
        buffers.push_back(frame.cmd);
    }
};

TEST(FramePasses, TheListRefusesWhatCannotWork)
{
    TransferClearPass clear;
    OverlayPass overlay;
    WitnessPass witness;
    // loading a target nothing has drawn yet
    EXPECT_THROW(FramePasses({&witness, &overlay, &clear}), std::invalid_argument);
    // a frame that draws nothing
    EXPECT_THROW(FramePasses({&witness}), std::invalid_argument);
    EXPECT_THROW(FramePasses({&clear, nullptr}), std::invalid_argument);
    EXPECT_NO_THROW(FramePasses({&witness, &clear, &overlay, &witness}));
    // a clearing pass may come after others: it starts the picture anew
    EXPECT_NO_THROW(FramePasses({&clear, &overlay, &clear}));
}

// Writes the whole target from a compute shader's place (layout GENERAL: a storage image).
struct StoragePass final : FramePass {
    const char* name() const override { return "storage write"; }
    TargetUse target_use() const override
    {
        return {{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT}, TargetLoad::clear};
    }
    void record(const PassContext&) override { ADD_FAILURE() << "recorded for a target it cannot use"; }
};

TEST(FramePasses, ATargetWithoutTheUsageAPassNeedsIsRefusedBeforeRecording)
{
    // a swapchain may offer a colour attachment only: a transfer clear or a storage write into it
    // is a wiring error, named, and nothing is recorded (no command buffer is needed to see it)
    TransferClearPass clear;
    StoragePass storage;
    OverlayPass overlay;
    WitnessPass witness;
    FrameTarget target;
    target.extent = kExtent;
    target.format = VK_FORMAT_B8G8R8A8_SRGB;
    target.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    const TargetState initial{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE};
    const TargetState final{VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
    const auto refusal = [&](const FramePasses& passes) -> std::string {
        try {
            passes.record(VK_NULL_HANDLE, 0, target, initial, final);
        } catch (const std::logic_error& e) {
            return e.what();
        }
        return "";
    };
    const std::string no_transfer = refusal(FramePasses{&witness, &clear, &overlay});
    EXPECT_NE(no_transfer.find("'transfer clear'"), std::string::npos) << no_transfer;
    EXPECT_NE(no_transfer.find("TRANSFER_DST"), std::string::npos) << no_transfer;
    EXPECT_TRUE(witness.slots.empty()) << "a pass was recorded before the refusal";
    const std::string no_storage = refusal(FramePasses{&storage});
    EXPECT_NE(no_storage.find("'storage write'"), std::string::npos) << no_storage;
    EXPECT_NE(no_storage.find("STORAGE"), std::string::npos) << no_storage;
    // the layouts and the usages they need (the offscreen target has them all: the test below)
    EXPECT_EQ(target_usage_for(VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL), VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_DST_BIT));
    EXPECT_EQ(target_usage_for(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT));
    EXPECT_EQ(target_usage_for(VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL), VkImageUsageFlags(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT));
}

TEST(FramePasses, EachPassGetsTheTargetInItsLayoutInOrder)
{
    TransferClearPass clear;
    OverlayPass overlay;
    WitnessPass witness;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    io::RgbaImage frames[3];
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        CommandPool commands(ctx);
        OffscreenPresenter presenter(commands, kExtent);
        // transfer destination, then colour attachment, then transfer source for the readback
        const FramePasses passes{&witness, &clear, &overlay};
        for (auto& f : frames) presenter.render(passes, &f);
        // only the clear: its layout goes straight to the readback's
        presenter.render(FramePasses{&clear}, &frames[2]);
    }
    EXPECT_EQ(messages->load(), 0u);

    // the witness ran once per frame, in slot after slot, in the frame's one command buffer
    EXPECT_EQ(witness.slots, (std::vector<int>{0, 1, 0}));
    ASSERT_EQ(witness.buffers.size(), 3u);
    EXPECT_NE(witness.buffers[0], VK_NULL_HANDLE);

    const std::uint8_t red[4] = {255, 0, 0, 255}, blue[4] = {0, 0, 255, 255};
    for (int f = 0; f < 2; ++f) {
        int wrong = 0;
        for (std::uint32_t y = 0; y < kExtent.height; ++y)
            for (std::uint32_t x = 0; x < kExtent.width; ++x) {
                const bool inside = x >= std::uint32_t(kRect.offset.x) && x < kRect.offset.x + kRect.extent.width &&
                                    y >= std::uint32_t(kRect.offset.y) && y < kRect.offset.y + kRect.extent.height;
                wrong += std::memcmp(frames[f].at(x, y), inside ? blue : red, 4) != 0;
            }
        EXPECT_EQ(wrong, 0) << "frame " << f << ": the overlay's rectangle blue on the clear's red expected";
    }
    for (std::uint32_t y = 0; y < kExtent.height; ++y)
        for (std::uint32_t x = 0; x < kExtent.width; ++x) ASSERT_EQ(std::memcmp(frames[2].at(x, y), red, 4), 0);
}

}  // namespace
}  // namespace echosim::gpu

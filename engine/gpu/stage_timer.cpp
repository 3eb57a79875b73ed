#include "gpu/stage_timer.hpp"

#include <stdexcept>
#include <string>

#include "gpu/context.hpp"
#include "gpu/vk_error.hpp"

namespace echosim::gpu {

StageTimer::StageTimer(const Context& ctx, int slots, std::size_t stages)
    : device_(ctx.device()), stages_(stages), period_ns_(ctx.limits().timestampPeriod), marked_(std::size_t(slots), 0)
{
    if (stages > 32) throw std::invalid_argument("stage timer: " + std::to_string(stages) + " stages, at most 32");
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device(), &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device(), &count, families.data());
    const std::uint32_t bits = ctx.queue_family() < count ? families[ctx.queue_family()].timestampValidBits : 0;
    if (bits == 0) throw std::runtime_error("stage timer: " + ctx.device_name() + "'s queue keeps no timestamps");
    valid_mask_ = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = std::uint32_t(std::size_t(slots) * (stages + 1));
    check(vkCreateQueryPool(device_, &info, nullptr, &pool_), "vkCreateQueryPool (stage timer)");
}

StageTimer::~StageTimer()
{
    if (pool_ != VK_NULL_HANDLE) vkDestroyQueryPool(device_, pool_, nullptr);
}

void StageTimer::begin(VkCommandBuffer cmd, int slot)
{
    vkCmdResetQueryPool(cmd, pool_, first(slot), std::uint32_t(stages_ + 1));
    marked_[std::size_t(slot)] = 0;
}

void StageTimer::mark(VkCommandBuffer cmd, int slot, std::size_t stage)
{
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, first(slot) + std::uint32_t(stage));
    marked_[std::size_t(slot)] |= 1u << stage;
}

void StageTimer::end(VkCommandBuffer cmd, int slot)
{
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, first(slot) + std::uint32_t(stages_));
}

std::vector<double> StageTimer::stage_ms(int slot) const
{
    std::vector<double> ms(stages_, -1.0);
    const std::uint32_t marked = marked_[std::size_t(slot)];
    if (marked == 0) return ms;
    std::vector<std::uint64_t> ticks(stages_ + 1, 0);
    // only the queries this frame wrote: an unwritten one would never become available
    for (std::size_t i = 0; i <= stages_; ++i) {
        if (i < stages_ && !(marked >> i & 1u)) continue;
        check(vkGetQueryPoolResults(device_, pool_, first(slot) + std::uint32_t(i), 1, sizeof(std::uint64_t), &ticks[i], sizeof(std::uint64_t),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults (stage timer)");
        ticks[i] &= valid_mask_;
    }
    for (std::size_t i = 0; i < stages_; ++i) {
        if (!(marked >> i & 1u)) continue;
        std::size_t next = i + 1;
        while (next < stages_ && !(marked >> next & 1u)) ++next;
        ms[i] = double(ticks[next] - ticks[i]) * period_ns_ * 1e-6;
    }
    return ms;
}

}  // namespace echosim::gpu

// GPU timestamps between the stages of a recorded pass (a StageList's), per frame slot: where a
// frame's GPU time goes, stage by stage, on the device that runs it (the benchmarks' breakdown; no
// profiler reads a lavapipe or a lent GPU's counters here). A timestamp is written as each stage
// starts, after its barriers (so after the stages before it finished), and one at the end: a
// stage's time is from its mark to the next one's. Off the hot path: made only when asked for.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

class Context;

class StageTimer {
public:
    // Throws std::runtime_error when the context's queue family keeps no timestamps.
    StageTimer(const Context& ctx, int slots, std::size_t stages);
    ~StageTimer();
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

    void begin(VkCommandBuffer cmd, int slot);                     // the slot's marks cleared
    void mark(VkCommandBuffer cmd, int slot, std::size_t stage);  // stage starts (after its barriers)
    void end(VkCommandBuffer cmd, int slot);                       // the last stage done
    // Each stage's milliseconds in the slot's last frame (-1 for a stage not recorded in it; a
    // stage quicker than a tick reads 0); valid once that frame's fence has signalled.
    std::vector<double> stage_ms(int slot) const;

private:
    VkDevice device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    std::size_t stages_;
    double period_ns_;  // a timestamp tick
    std::uint64_t valid_mask_;
    std::vector<std::uint32_t> marked_;  // per slot, bit i: stage i marked in its last frame
    std::uint32_t first(int slot) const { return std::uint32_t(std::size_t(slot) * (stages_ + 1)); }
};

}  // namespace echosim::gpu

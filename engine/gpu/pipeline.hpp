// A pipeline (graphics or compute) and the layout it was made with, released together. The layout:
// one descriptor set layout and, when `push.size` is not zero, one push-constant range. The owner
// waits for the device before it lets one go (gpu/frame.hpp, "Lifetime").
#pragma once

#include <functional>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

class Pipeline {
public:
    // Makes the layout, then the pipeline on it with `make`; throws naming `name` if either fails
    // (and then releases the layout).
    Pipeline(VkDevice device, VkDescriptorSetLayout set_layout, VkPushConstantRange push, const char* name,
             const std::function<VkPipeline(VkPipelineLayout)>& make);
    ~Pipeline();
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    VkPipelineLayout layout() const { return layout_; }
    VkPipeline handle() const { return pipeline_; }

private:
    VkDevice device_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace echosim::gpu

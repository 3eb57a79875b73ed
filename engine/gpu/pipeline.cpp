#include "gpu/pipeline.hpp"

#include <string>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {

Pipeline::Pipeline(VkDevice device, VkDescriptorSetLayout set_layout, VkPushConstantRange push, const char* name,
                   const std::function<VkPipeline(VkPipelineLayout)>& make)
    : device_(device)
{
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = set_layout != VK_NULL_HANDLE ? 1 : 0;  // none: push constants alone
    info.pSetLayouts = &set_layout;
    info.pushConstantRangeCount = push.size > 0 ? 1 : 0;
    info.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(device, &info, nullptr, &layout_), ("vkCreatePipelineLayout (" + std::string(name) + ")").c_str());
    try {
        pipeline_ = make(layout_);
    } catch (...) {
        vkDestroyPipelineLayout(device, layout_, nullptr);
        throw;
    }
}

Pipeline::~Pipeline()
{
    vkDestroyPipeline(device_, pipeline_, nullptr);
    vkDestroyPipelineLayout(device_, layout_, nullptr);
}

}  // namespace echosim::gpu

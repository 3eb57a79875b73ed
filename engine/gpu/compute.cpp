#include "gpu/compute.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/renderer.hpp"  // create_shader_module
#include "gpu/vk_error.hpp"

namespace echosim::gpu {

ComputeKernel::ComputeKernel(const Context& ctx, std::span<const std::uint32_t> spirv, const char* name,
                             std::uint32_t storage_buffers, std::uint32_t push_bytes)
    : ctx_(ctx), name_(name), storage_buffers_(storage_buffers), push_bytes_(push_bytes)
{
    const VkDevice dev = ctx.device();
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings(storage_buffers);
        for (std::uint32_t i = 0; i < storage_buffers; ++i)
            bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = storage_buffers;
        set_info.pBindings = bindings.data();
        check(vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &set_layout_), "vkCreateDescriptorSetLayout (compute)");

        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_buffers};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
        check(vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool_), "vkCreateDescriptorPool (compute)");
        VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        alloc.descriptorPool = pool_;
        alloc.descriptorSetCount = 1;
        alloc.pSetLayouts = &set_layout_;
        check(vkAllocateDescriptorSets(dev, &alloc, &set_), "vkAllocateDescriptorSets (compute)");

        VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout_;
        layout_info.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
        layout_info.pPushConstantRanges = &push;
        check(vkCreatePipelineLayout(dev, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout (compute)");

        VkShaderModule module = create_shader_module(dev, spirv, name);
        VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
        info.layout = layout_;
        const VkResult result = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
        vkDestroyShaderModule(dev, module, nullptr);
        check(result, (std::string("vkCreateComputePipelines ") + name).c_str());
    } catch (...) {
        destroy();
        throw;
    }
}

ComputeKernel::~ComputeKernel() { destroy(); }

void ComputeKernel::destroy()
{
    const VkDevice dev = ctx_.device();
    if (pipeline_) vkDestroyPipeline(dev, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
    if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

void ComputeKernel::bind(std::span<const Buffer* const> buffers)
{
    if (buffers.size() != storage_buffers_)
        throw std::invalid_argument(std::string(name_) + ": " + std::to_string(buffers.size()) + " buffers bound, kernel has " +
                                    std::to_string(storage_buffers_) + " bindings");
    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes(buffers.size());
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = set_;
        writes[i].dstBinding = std::uint32_t(i);
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(ctx_.device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void ComputeKernel::record(VkCommandBuffer cmd, std::span<const std::byte> push, std::uint32_t groups) const
{
    if (push.size() != push_bytes_)
        throw std::invalid_argument(std::string(name_) + ": push constants of " + std::to_string(push.size()) +
                                    " bytes, kernel expects " + std::to_string(push_bytes_));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    if (push_bytes_ > 0) vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push.data());
    vkCmdDispatch(cmd, groups, 1, 1);
}

}  // namespace echosim::gpu

#include "gpu/compute.hpp"

#include <stdexcept>
#include <string>

#include "gpu/shader.hpp"
#include "gpu/vk_error.hpp"

namespace echosim::gpu {
namespace {

std::uint32_t groups_for(std::uint32_t items, std::uint32_t group)
{
    if (group == 0) throw std::invalid_argument("a workgroup of size 0");
    // not (items + group - 1) / group: that wraps for items near UINT32_MAX
    return items / group + (items % group != 0 ? 1u : 0u);
}

// A compute pipeline of `spirv` on `layout` with specialization constant 0 set to `variant`.
VkPipeline make_pipeline(VkDevice dev, VkPipelineLayout layout, std::span<const std::uint32_t> spirv, const char* name, std::uint32_t variant)
{
    VkShaderModule module = create_shader_module(dev, spirv, name);
    const VkSpecializationMapEntry entry{0, 0, sizeof(std::uint32_t)};
    const VkSpecializationInfo specialization{1, &entry, sizeof(variant), &variant};
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", &specialization};
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult result = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(dev, module, nullptr);
    check(result, (std::string("vkCreateComputePipelines ") + name + " (variant " + std::to_string(variant) + ")").c_str());
    return pipeline;
}

}  // namespace

Groups Groups::cover(std::uint32_t items, std::uint32_t group) { return {groups_for(items, group), 1, 1}; }

Groups Groups::cover(VkExtent2D items, VkExtent2D group)
{
    return {groups_for(items.width, group.width), groups_for(items.height, group.height), 1};
}

Groups Groups::cover(VkExtent3D items, VkExtent3D group)
{
    return {groups_for(items.width, group.width), groups_for(items.height, group.height), groups_for(items.depth, group.depth)};
}

ComputeKernel::ComputeKernel(const Context& ctx, std::span<const std::uint32_t> spirv, const char* name,
                             std::span<const BindingKind> bindings, std::uint32_t push_bytes)
    : ctx_(ctx), name_(name), push_bytes_(push_bytes), descriptors_(ctx, bindings, VK_SHADER_STAGE_COMPUTE_BIT, name),
      pipeline_(ctx.device(), descriptors_.layout(), {VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes}, name,
                [&](VkPipelineLayout layout) { return make_pipeline(ctx.device(), layout, spirv, name, 0); }),
      spirv_(spirv)
{
}

// frames in flight may still dispatch it (gpu/frame.hpp, "Lifetime"); the pipeline and the
// descriptor sets go after this, with their members
ComputeKernel::~ComputeKernel()
{
    ctx_.wait_idle();
    for (const Variant& v : variants_) vkDestroyPipeline(ctx_.device(), v.pipeline, nullptr);
}

VkPipeline ComputeKernel::variant(std::uint32_t value) const
{
    if (value == 0) return pipeline_.handle();
    for (const Variant& v : variants_)
        if (v.value == value) return v.pipeline;
    variants_.reserve(variants_.size() + 1);  // so the push_back below cannot throw with the pipeline made
    variants_.push_back({value, make_pipeline(ctx_.device(), pipeline_.layout(), spirv_, name_, value)});
    return variants_.back().pipeline;
}

void ComputeKernel::record(VkCommandBuffer cmd, int slot, std::span<const std::byte> push, Groups groups, std::uint32_t variant_value) const
{
    if (push.size() != push_bytes_)
        throw std::invalid_argument(std::string(name_) + ": push constants of " + std::to_string(push.size()) +
                                    " bytes, kernel expects " + std::to_string(push_bytes_));
    if (slot < 0 || slot >= kFramesInFlight)
        throw std::out_of_range(std::string(name_) + ": frame slot " + std::to_string(slot) + " does not exist");
    if (!descriptors_.bound(slot))
        throw std::logic_error(std::string(name_) + ": slot " + std::to_string(slot) + " dispatched before its resources were bound");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, variant(variant_value));
    if (descriptors_.size() > 0) {
        const VkDescriptorSet set = descriptors_.set(slot);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.layout(), 0, 1, &set, 0, nullptr);
    }
    if (push_bytes_ > 0) vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push.data());
    vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
}

}  // namespace echosim::gpu

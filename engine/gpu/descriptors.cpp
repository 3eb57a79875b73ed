#include "gpu/descriptors.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <stdexcept>
#include <utility>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {
namespace {

VkDescriptorType descriptor_type(BindingKind kind)
{
    switch (kind) {
    case BindingKind::storage_buffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingKind::uniform_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingKind::storage_image: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case BindingKind::sampled_image: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case BindingKind::texel_buffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    }
    return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

const char* kind_name(BindingKind kind)
{
    switch (kind) {
    case BindingKind::storage_buffer: return "storage buffer";
    case BindingKind::uniform_buffer: return "uniform buffer";
    case BindingKind::storage_image: return "storage image";
    case BindingKind::sampled_image: return "sampled image";
    case BindingKind::texel_buffer: return "texel buffer";
    }
    return "?";
}

}  // namespace

SlotDescriptors::SlotDescriptors(const Context& ctx, std::span<const BindingKind> kinds, VkShaderStageFlags stages,
                                 std::string owner)
    : ctx_(ctx), owner_(std::move(owner)), kinds_(kinds.begin(), kinds.end())
{
    const VkDevice dev = ctx.device();
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings(kinds_.size());
        std::array<std::uint32_t, 5> per_kind{};  // descriptors of each kind in one set
        for (std::uint32_t i = 0; i < kinds_.size(); ++i) {
            bindings[i] = {i, descriptor_type(kinds_[i]), 1, stages, nullptr};
            ++per_kind[std::size_t(kinds_[i])];
        }
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = std::uint32_t(bindings.size());
        set_info.pBindings = bindings.data();
        check(vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &layout_), ("vkCreateDescriptorSetLayout " + owner_).c_str());
        if (kinds_.empty()) {
            // a kernel with push constants only: nothing to allocate, and every slot ready as it is
            std::fill(std::begin(bound_), std::end(bound_), true);
            return;
        }

        std::vector<VkDescriptorPoolSize> sizes;
        for (std::size_t k = 0; k < per_kind.size(); ++k)
            if (per_kind[k] > 0) sizes.push_back({descriptor_type(BindingKind(k)), per_kind[k] * kFramesInFlight});
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = kFramesInFlight;
        pool_info.poolSizeCount = std::uint32_t(sizes.size());
        pool_info.pPoolSizes = sizes.data();
        check(vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool_), ("vkCreateDescriptorPool " + owner_).c_str());
        std::array<VkDescriptorSetLayout, kFramesInFlight> layouts;
        layouts.fill(layout_);
        VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        alloc.descriptorPool = pool_;
        alloc.descriptorSetCount = kFramesInFlight;
        alloc.pSetLayouts = layouts.data();
        check(vkAllocateDescriptorSets(dev, &alloc, sets_), ("vkAllocateDescriptorSets " + owner_).c_str());
    } catch (...) {
        destroy();
        throw;
    }
}

SlotDescriptors::~SlotDescriptors() { destroy(); }

void SlotDescriptors::destroy()
{
    const VkDevice dev = ctx_.device();
    if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);  // frees the sets
    if (layout_) vkDestroyDescriptorSetLayout(dev, layout_, nullptr);
    pool_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
}

void SlotDescriptors::bind(int slot, std::span<const Binding> resources)
{
    const std::string who = owner_ + " slot " + std::to_string(slot);
    if (slot < 0 || slot >= kFramesInFlight)
        throw std::out_of_range(who + ": frame slots are 0.." + std::to_string(kFramesInFlight - 1));
    if (resources.size() != kinds_.size())
        throw std::invalid_argument(who + ": " + std::to_string(resources.size()) + " resources bound, " +
                                    std::to_string(kinds_.size()) + " bindings declared");
    std::vector<VkDescriptorBufferInfo> buffers(resources.size());
    std::vector<VkDescriptorImageInfo> images(resources.size());
    std::vector<VkBufferView> views(resources.size());
    std::vector<VkWriteDescriptorSet> writes(resources.size());
    for (std::size_t i = 0; i < resources.size(); ++i) {
        const Binding& r = resources[i];
        const std::string where = who + " binding " + std::to_string(i);
        if (r.kind != kinds_[i])
            throw std::invalid_argument(where + ": a " + kind_name(r.kind) + " given, a " + kind_name(kinds_[i]) + " declared");
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = sets_[slot];
        writes[i].dstBinding = std::uint32_t(i);
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = descriptor_type(r.kind);
        switch (r.kind) {
        case BindingKind::storage_buffer:
        case BindingKind::uniform_buffer:
            if (!r.buffer) throw std::invalid_argument(where + ": no buffer");
            buffers[i] = {r.buffer->handle(), 0, VK_WHOLE_SIZE};
            writes[i].pBufferInfo = &buffers[i];
            break;
        case BindingKind::storage_image:
            if (!r.image) throw std::invalid_argument(where + ": no image");
            images[i] = {VK_NULL_HANDLE, r.image->view(), VK_IMAGE_LAYOUT_GENERAL};
            writes[i].pImageInfo = &images[i];
            break;
        case BindingKind::sampled_image:
            if (!r.image || !r.sampler) throw std::invalid_argument(where + ": needs an image and a sampler");
            images[i] = {r.sampler->handle(), r.image->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            writes[i].pImageInfo = &images[i];
            break;
        case BindingKind::texel_buffer:
            if (!r.texels) throw std::invalid_argument(where + ": no texel view");
            views[i] = r.texels->handle();
            writes[i].pTexelBufferView = &views[i];
            break;
        }
    }
    vkUpdateDescriptorSets(ctx_.device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    bound_[slot] = true;
}

}  // namespace echosim::gpu

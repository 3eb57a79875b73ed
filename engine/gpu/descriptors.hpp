// Descriptor bindings of several kinds, and one descriptor set of them per frame slot: what a
// compute kernel or a graphics pass reads and writes, pointed at the resources of the frame being
// recorded while the GPU may still run the other slot's frame.
//
// Lifetime: destruction waits for nothing; the owner (a pass, a compute kernel) waits for the
// device first (gpu/frame.hpp, "Lifetime").
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"

namespace echosim::gpu {

// The kinds of binding a set declares, binding i being kinds[i].
enum class BindingKind {
    storage_buffer,  // buffer, read and written (GLSL `buffer`)
    uniform_buffer,  // buffer, read only, small (GLSL `uniform`)
    storage_image,   // image in layout GENERAL, imageLoad/imageStore (GLSL `image2D`, `image3D`)
    sampled_image,   // image in layout SHADER_READ_ONLY_OPTIMAL with a sampler (GLSL `sampler2D`, `sampler3D`)
    texel_buffer,    // buffer read through a TexelView (GLSL `samplerBuffer`, texelFetch)
};

// What one binding points at, of the kind declared for it.
struct Binding {
    BindingKind kind = BindingKind::storage_buffer;
    const Buffer* buffer = nullptr;
    const Image* image = nullptr;
    const Sampler* sampler = nullptr;
    const TexelView* texels = nullptr;

    static Binding storage(const Buffer& b) { return {BindingKind::storage_buffer, &b, nullptr, nullptr}; }
    static Binding uniform(const Buffer& b) { return {BindingKind::uniform_buffer, &b, nullptr, nullptr}; }
    static Binding storage(const Image& i) { return {BindingKind::storage_image, nullptr, &i, nullptr}; }
    static Binding sampled(const Image& i, const Sampler& s) { return {BindingKind::sampled_image, nullptr, &i, &s}; }
    static Binding texel(const TexelView& t) { return {BindingKind::texel_buffer, nullptr, nullptr, nullptr, &t}; }
};

// A descriptor set layout of the declared kinds (set 0 of a pipeline) and one set per frame slot.
class SlotDescriptors {
public:
    // `owner` names the kernel or pass in errors; `stages` are the shader stages that read the set.
    SlotDescriptors(const Context& ctx, std::span<const BindingKind> kinds, VkShaderStageFlags stages, std::string owner);
    ~SlotDescriptors();
    SlotDescriptors(const SlotDescriptors&) = delete;
    SlotDescriptors& operator=(const SlotDescriptors&) = delete;

    VkDescriptorSetLayout layout() const { return layout_; }
    VkDescriptorSet set(int slot) const { return sets_[std::size_t(slot)]; }
    // whether the slot's set points at resources: bind() was called for it, or there is nothing to bind
    bool bound(int slot) const { return bound_[std::size_t(slot)]; }
    std::size_t size() const { return kinds_.size(); }

    // Points slot `slot`'s bindings at these resources (binding i = resources[i], of the declared
    // kind); throws on a wrong slot, count or kind. Only while the GPU is done with the slot's last
    // frame: at set-up (before any frame), or from inside the owning pass's record() for that very
    // slot (the presenter has waited for the slot's previous frame, gpu/frame.hpp); never from a
    // caller outside the frame, which cannot know which slot is idle.
    void bind(int slot, std::span<const Binding> resources);

private:
    void destroy();
    const Context& ctx_;
    std::string owner_;
    std::vector<BindingKind> kinds_;
    VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet sets_[kFramesInFlight]{};
    bool bound_[kFramesInFlight]{};
};

}  // namespace echosim::gpu

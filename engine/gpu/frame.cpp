#include "gpu/frame.hpp"

#include <stdexcept>
#include <string>

#include "gpu/resources.hpp"

namespace echosim::gpu {

TargetUse TargetUse::color_attachment(TargetLoad load)
{
    TargetUse use;
    use.state.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    use.state.stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    // loading reads what the passes before left (and blending may read it too)
    use.state.access = load == TargetLoad::clear
                           ? VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT
                           : VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    use.load = load;
    return use;
}

VkImageUsageFlags target_usage_for(VkImageLayout layout)
{
    switch (layout) {
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case VK_IMAGE_LAYOUT_GENERAL: return VK_IMAGE_USAGE_STORAGE_BIT;
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return VK_IMAGE_USAGE_SAMPLED_BIT;
    default: return 0;
    }
}

namespace {

const char* usage_name(VkImageUsageFlags usage)
{
    switch (usage) {
    case VK_IMAGE_USAGE_TRANSFER_DST_BIT: return "TRANSFER_DST";
    case VK_IMAGE_USAGE_TRANSFER_SRC_BIT: return "TRANSFER_SRC";
    case VK_IMAGE_USAGE_STORAGE_BIT: return "STORAGE";
    case VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT: return "COLOR_ATTACHMENT";
    case VK_IMAGE_USAGE_SAMPLED_BIT: return "SAMPLED";
    default: return "?";
    }
}

}  // namespace

FramePasses::FramePasses(std::initializer_list<FramePass*> passes) : FramePasses(std::span(passes.begin(), passes.size())) {}

FramePasses::FramePasses(std::span<FramePass* const> passes)
{
    bool drawn = false;  // whether a pass before has given the target its contents
    for (std::size_t i = 0; i < passes.size(); ++i) {
        FramePass* pass = passes[i];
        if (!pass) throw std::invalid_argument("frame pass " + std::to_string(i) + " is null");
        const TargetUse use = pass->target_use();
        if (use.touches_target()) {
            if (use.state.layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
                throw std::invalid_argument(std::string("frame pass '") + pass->name() + "' asks for the target in no usable layout");
            if (use.load == TargetLoad::load && !drawn)
                throw std::invalid_argument(std::string("frame pass '") + pass->name() +
                                            "' loads the target but no pass before it clears it");
            drawn = true;
        }
        passes_.push_back({pass, use});
    }
    if (!drawn) throw std::invalid_argument("no pass of the frame draws its target");
}

void FramePasses::record(VkCommandBuffer cmd, int slot, const FrameTarget& target, const TargetState& initial,
                         const TargetState& final) const
{
    // a wiring error (a pass on a presenter whose target cannot serve it): refused before any
    // command is recorded, rather than left to the validation layer
    for (const Entry& e : passes_) {
        const VkImageUsageFlags needed = target_usage_for(e.use.state.layout);
        if (e.use.touches_target() && (target.usage & needed) != needed)
            throw std::logic_error(std::string("frame pass '") + e.pass->name() + "' needs the target with usage " +
                                   usage_name(needed) + ", which this target lacks");
    }

    const PassContext frame{cmd, slot, target};
    TargetState current = initial;
    for (const Entry& e : passes_) {
        if (e.use.touches_target()) {
            // one barrier before every pass that uses the target: each of ours writes it, so even
            // passes in the same layout need the previous writes done and visible (an overlay
            // blending over the scene); a clearing pass lets what was there be discarded
            const VkImageLayout from = e.use.load == TargetLoad::clear ? VK_IMAGE_LAYOUT_UNDEFINED : current.layout;
            transition(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, from, e.use.state.layout, current.stage,
                       current.access, e.use.state.stage, e.use.state.access);
            current = e.use.state;
        }
        e.pass->record(frame);
    }
    transition(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, current.layout, final.layout, current.stage, current.access,
               final.stage, final.access);
}

}  // namespace echosim::gpu

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

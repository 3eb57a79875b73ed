// A frame as an ordered list of passes (Filament's FrameGraph and Granite's render graph, at our
// scale: a fixed order and declared layouts, not a general graph).
//
// A presenter (window or offscreen) owns the frame's target, a colour image, and hands it to each
// pass in turn: compute passes, the 3D scene, further views (the echographic image panel), a UI
// overlay. Each pass declares once what it needs of the target: the layout, the pipeline stages and
// accesses it uses it with, and whether it clears it (draws all of it anew) or loads it (draws over
// what the passes before it left). The frame recorder below, shared by both presenters, places the
// barrier before each pass that uses the target and the last one into the presenter's final layout
// (present, or transfer source for readback):
//
//   initial ──▶ [pass 1: clear, colour attachment] ──▶ [pass 2: load, colour attachment] ──▶ final
//           barrier                                barrier                               barrier
//
// A pass that does not touch the target (a compute pass filling the echographic image) gets no
// barrier; the resources it shares with later passes are its own to synchronise (it leaves them in
// the layout, stage and access its readers expect, documented with the pass).
//
// The target's usage: each pass's layout needs a usage of the target (a transfer destination, a
// storage image, a colour attachment, a sampled image); a presenter may not offer all of them (a
// swapchain without TRANSFER_DST), and recording a frame for a target without what a pass needs is
// a wiring error, refused before anything is recorded.
//
// Frame slots: up to kFramesInFlight frames may be in flight. A pass keeps per-slot copies of what
// it rewrites every frame (uniforms, vertices, descriptor sets); when it records slot s, the GPU is
// done with the previous frame of slot s (the presenter waited for its fence), and only then: so a
// pass re-points slot s's descriptor sets from inside its record() for slot s (or at set-up, before
// any frame), never from outside, where the caller cannot know which slot is idle.
//
// Lifetime: frames in flight may still use a pass's GPU objects (pipelines, descriptor sets,
// per-slot buffers and images, compute kernels) after its last record(). So every pass, and every
// GPU object a pass owns that waits for nothing itself (ComputeKernel does; SlotDescriptors and the
// resources of resources.hpp do not: their owners do), waits for the device (Context::wait_idle)
// before it is destroyed. Destruction is tear-down work, never per frame.
//
// Threading: the passes of a frame are recorded on the thread that calls the presenter, into the
// command buffers of that thread's pool; the frame is submitted through the Context.
#pragma once

#include <initializer_list>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

inline constexpr int kFramesInFlight = 2;

// The image a frame is drawn into (an offscreen image, or the swapchain image of this frame).
struct FrameTarget {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkExtent2D extent{};
    VkFormat format = VK_FORMAT_UNDEFINED;
    // always a colour attachment; a transfer destination too (clears, blits) where the presenter
    // can offer it: offscreen always, a swapchain where the surface allows. FramePasses::record
    // checks each pass's layout against it.
    VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
};

// A layout of the target and the stages and accesses that use it in that layout.
struct TargetState {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// Whether a pass draws the whole target anew (what was there before is discarded) or draws over it.
enum class TargetLoad { clear, load };

// What a pass needs of the target.
struct TargetUse {
    TargetState state;  // layout UNDEFINED: the pass does not touch the target
    TargetLoad load = TargetLoad::load;

    static TargetUse none() { return {}; }
    // The target as the one colour attachment of a graphics pass (dynamic rendering).
    static TargetUse color_attachment(TargetLoad load);

    bool touches_target() const { return state.layout != VK_IMAGE_LAYOUT_UNDEFINED; }
    // The load operation a graphics pass sets on its colour attachment to keep its declaration.
    VkAttachmentLoadOp attachment_load_op() const
    {
        return load == TargetLoad::clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    }
};

// The usage an image needs to be used in `layout` by a pass (TRANSFER_DST_OPTIMAL: TRANSFER_DST,
// GENERAL: STORAGE, COLOR_ATTACHMENT_OPTIMAL: COLOR_ATTACHMENT, SHADER_READ_ONLY_OPTIMAL: SAMPLED,
// TRANSFER_SRC_OPTIMAL: TRANSFER_SRC); 0 for a layout that asks for no particular one.
VkImageUsageFlags target_usage_for(VkImageLayout layout);

// What a pass records with: the frame's command buffer, its slot in [0, kFramesInFlight), and the
// target, already in the layout the pass declared.
struct PassContext {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    int slot = 0;
    const FrameTarget& target;
};

class FramePass {
public:
    virtual ~FramePass() = default;
    virtual const char* name() const = 0;
    // Asked once, when the pass joins a FramePasses list: a pass always needs the same of the target.
    virtual TargetUse target_use() const = 0;
    // Records the pass; must not change the target's layout (the recorder does) nor submit.
    virtual void record(const PassContext& frame) = 0;
};

// The ordered passes of a frame and the recorder that runs them. Made once (set-up: the list is
// checked here and throws std::invalid_argument naming the pass at fault), recorded every frame.
// The passes are not owned: they must outlive the list.
class FramePasses {
public:
    FramePasses(std::initializer_list<FramePass*> passes);
    explicit FramePasses(std::span<FramePass* const> passes);

    std::size_t size() const { return passes_.size(); }

    // Records every pass into `cmd` for frame slot `slot`, with the barriers between them: the
    // target starts in `initial` (the presenter's: its layout, and the stage its wait or last use
    // happened at) and is left in `final` (layout, and the stage and access of its next user).
    // Throws std::logic_error naming the pass and the usage, before recording anything, when a
    // pass needs the target in a layout its usage does not allow (target_usage_for).
    void record(VkCommandBuffer cmd, int slot, const FrameTarget& target, const TargetState& initial,
                const TargetState& final) const;

private:
    struct Entry {
        FramePass* pass;
        TargetUse use;
    };
    std::vector<Entry> passes_;
};

}  // namespace echosim::gpu

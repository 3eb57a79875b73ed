#include "gpu/stage_list.hpp"

#include <stdexcept>

#include "gpu/resources.hpp"

namespace echosim::gpu {

StageList::StageList(std::vector<StageResourceDecl> resources, std::vector<StageDecl> stages)
    : resources_(std::move(resources)), stages_(std::move(stages))
{
    if (stages_.size() > 32) throw std::invalid_argument("stage list: " + std::to_string(stages_.size()) + " stages, at most 32");
    for (const StageDecl& s : stages_)
        for (const auto* list : {&s.reads, &s.writes})
            for (const StageAccess& a : *list) {
                if (a.resource < 0 || std::size_t(a.resource) >= resources_.size())
                    throw std::invalid_argument("stage '" + s.name + "': resource " + std::to_string(a.resource) + " is not declared");
                const StageResourceDecl& r = resources_[std::size_t(a.resource)];
                if (r.image != (a.layout != VK_IMAGE_LAYOUT_UNDEFINED))
                    throw std::invalid_argument("stage '" + s.name + "': resource '" + r.name + "': " +
                                                (r.image ? "an image needs the layout the stage uses it in" : "a buffer has no layout"));
                if (a.stage == VK_PIPELINE_STAGE_2_NONE)
                    throw std::invalid_argument("stage '" + s.name + "': resource '" + r.name + "': no pipeline stage");
            }
}

int StageList::stage_index(const std::string& name) const
{
    for (std::size_t i = 0; i < stages_.size(); ++i)
        if (stages_[i].name == name) return int(i);
    return -1;
}

namespace {

// What the recorder knows of a resource within one recording.
struct Tracked {
    VkPipelineStageFlags2 write_stage = VK_PIPELINE_STAGE_2_NONE;  // the last write (NONE: none this recording)
    VkAccessFlags2 write_access = VK_ACCESS_2_NONE;
    VkPipelineStageFlags2 read_stages = VK_PIPELINE_STAGE_2_NONE;  // reads since that write
    VkPipelineStageFlags2 visible_stages = VK_PIPELINE_STAGE_2_NONE;  // the write made visible to
    VkAccessFlags2 visible_access = VK_ACCESS_2_NONE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

// The barrier one access needs before it, on `t`; images' transitions recorded at once, buffers'
// (and images' without a layout change) gathered into `src`/`dst` for one memory barrier.
void before(VkCommandBuffer cmd, VkImage image, Tracked& t, const StageAccess& a, bool write, VkPipelineStageFlags2& src_stage,
            VkAccessFlags2& src_access, VkPipelineStageFlags2& dst_stage, VkAccessFlags2& dst_access)
{
    const bool relayout = image != VK_NULL_HANDLE && a.layout != t.layout;
    VkPipelineStageFlags2 s_stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 s_access = VK_ACCESS_2_NONE;
    const bool written = t.write_stage != VK_PIPELINE_STAGE_2_NONE;
    // a write, and a layout transition (which writes the image), wait for the reads before them
    if (write || relayout) s_stage |= t.read_stages;
    if (write) {
        if (written) s_stage |= t.write_stage, s_access |= t.write_access;  // write after write
    } else if (written && ((t.visible_stages & a.stage) != a.stage || (t.visible_access & a.access) != a.access)) {
        s_stage |= t.write_stage, s_access |= t.write_access;  // read after write, not yet visible to it
    }
    if (relayout) {
        const VkImageLayout from = write && a.discard ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout;
        transition(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, from, a.layout, s_stage, s_access, a.stage, a.access);
        t.layout = a.layout;
    } else if (s_stage != VK_PIPELINE_STAGE_2_NONE) {
        src_stage |= s_stage, src_access |= s_access;
        dst_stage |= a.stage, dst_access |= a.access;
    }
    if (!write && (relayout || s_stage != VK_PIPELINE_STAGE_2_NONE || written))
        t.visible_stages |= a.stage, t.visible_access |= a.access;
}

}  // namespace

void StageList::record(VkCommandBuffer cmd, std::uint32_t active, std::span<const VkImage> images, std::span<const StageAccess> final,
                       const std::function<void(std::size_t stage)>& record_stage) const
{
    if (images.size() != resources_.size())
        throw std::invalid_argument("stage list: " + std::to_string(images.size()) + " image handles for " + std::to_string(resources_.size()) +
                                    " resources");
    std::vector<Tracked> tracked(resources_.size());
    for (std::size_t i = 0; i < stages_.size(); ++i) {
        if (!(active & (1u << i))) continue;
        const StageDecl& s = stages_[i];
        VkPipelineStageFlags2 src_stage = VK_PIPELINE_STAGE_2_NONE, dst_stage = VK_PIPELINE_STAGE_2_NONE;
        VkAccessFlags2 src_access = VK_ACCESS_2_NONE, dst_access = VK_ACCESS_2_NONE;
        for (const StageAccess& a : s.reads)
            before(cmd, images[std::size_t(a.resource)], tracked[std::size_t(a.resource)], a, false, src_stage, src_access, dst_stage, dst_access);
        for (const StageAccess& a : s.writes)
            before(cmd, images[std::size_t(a.resource)], tracked[std::size_t(a.resource)], a, true, src_stage, src_access, dst_stage, dst_access);
        if (src_stage != VK_PIPELINE_STAGE_2_NONE) memory_barrier(cmd, src_stage, src_access, dst_stage, dst_access);
        record_stage(i);
        for (const StageAccess& a : s.reads) tracked[std::size_t(a.resource)].read_stages |= a.stage;
        for (const StageAccess& a : s.writes) {
            Tracked& t = tracked[std::size_t(a.resource)];
            t.write_stage = a.stage;
            t.write_access = a.access;
            t.read_stages = VK_PIPELINE_STAGE_2_NONE;
            t.visible_stages = VK_PIPELINE_STAGE_2_NONE;
            t.visible_access = VK_ACCESS_2_NONE;
        }
    }
    // the images handed on to their next reader
    for (const StageAccess& a : final) {
        Tracked& t = tracked[std::size_t(a.resource)];
        const VkImage image = images[std::size_t(a.resource)];
        if (image == VK_NULL_HANDLE || t.write_stage == VK_PIPELINE_STAGE_2_NONE) continue;  // not written: nothing to hand on
        VkPipelineStageFlags2 src_stage = VK_PIPELINE_STAGE_2_NONE, dst_stage = VK_PIPELINE_STAGE_2_NONE;
        VkAccessFlags2 src_access = VK_ACCESS_2_NONE, dst_access = VK_ACCESS_2_NONE;
        before(cmd, image, t, a, false, src_stage, src_access, dst_stage, dst_access);
        if (src_stage != VK_PIPELINE_STAGE_2_NONE) memory_barrier(cmd, src_stage, src_access, dst_stage, dst_access);
    }
}

}  // namespace echosim::gpu

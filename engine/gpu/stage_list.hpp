// The stages of a compute pass (the echographic image pipeline's deform ▶ slice+post ▶ display
// copy, and whatever joins it: a B-mode stage) as a small list of sub-passes that declare what they
// read and write, so one recorder places the barriers between them instead of each stage's author
// (Granite's render graph at the scale of one pass: a fixed order, declared accesses).
//
// A stage declares, for each resource it touches (a buffer, or an image with the layout it needs),
// the pipeline stage and the access it uses it with. Recording the active stages in order, the
// recorder tracks each resource's last write and the stages that read it since, and before a stage
// puts:
//   - a read after a write: the write made available and visible to the reader (once per reader
//     stage and access: a second reader of the same kind needs nothing more);
//   - a write after a read or a write: the reads done (an execution dependency) and the write ordered;
//   - an image in another layout than the stage needs: its transition (from UNDEFINED where the
//     stage discards what the image held);
// buffers' hazards merged into one global memory barrier a stage, as a compute chain wants, images'
// into their transitions. At the end each image resource is left as the list's caller declares
// (the layout, stage and access of its next reader: the image panel, a read-back copy).
//
// Made once (the declarations checked, std::invalid_argument naming the stage and the resource at
// fault); recorded every frame with that frame's image handles (frame slots have their own images).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

struct StageAccess {
    int resource = 0;  // index into the list's resources
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images: the layout the stage uses it in
    bool discard = false;  // a write that replaces all the image held (its old contents need not survive)
};

struct StageDecl {
    std::string name;
    std::vector<StageAccess> reads, writes;
};

struct StageResourceDecl {
    std::string name;
    bool image = false;
};

class StageList {
public:
    StageList(std::vector<StageResourceDecl> resources, std::vector<StageDecl> stages);

    std::size_t size() const { return stages_.size(); }
    const StageDecl& stage(std::size_t i) const { return stages_[i]; }
    const std::vector<StageResourceDecl>& resources() const { return resources_; }
    int stage_index(const std::string& name) const;  // -1 when none is called so

    // Records the stages whose bit is set in `active` (bit i: stage i), in order, each through
    // `record_stage(i)`, with the barriers they declared; `images[r]` is resource r's image this
    // frame (VK_NULL_HANDLE for buffers), each starting UNDEFINED; `final` says how each image
    // resource the stages wrote is left (its layout, and its next reader's stage and access).
    void record(VkCommandBuffer cmd, std::uint32_t active, std::span<const VkImage> images, std::span<const StageAccess> final,
                const std::function<void(std::size_t stage)>& record_stage) const;

private:
    std::vector<StageResourceDecl> resources_;
    std::vector<StageDecl> stages_;
};

}  // namespace echosim::gpu

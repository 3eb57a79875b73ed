#include "echo/deform_cpu.hpp"

#include <cmath>
#include <stdexcept>
#include <string>


namespace echosim::echo {
namespace kernels_cpu {

using namespace echosim::kernels;

// The kernel's body as a member function: the accessors it calls are this class' members, as they
// are the shader's globals on the GPU.
class DeformColumns {
public:
    DeformColumns(const io::Volume* labels, std::span<const ColumnProfile> profile, const TissueTable& tissues, std::vector<uvec2>& scratch,
                  std::uint32_t max_steps, std::vector<float>& moved, std::vector<uint>& walls, std::vector<glm::vec2>& map)
        : labels_(labels), profile_(profile), tissues_(tissues), scratch_(scratch), max_steps_(max_steps), moved_(moved), walls_(walls),
          map_(map)
    {
    }

#include "deform_column.h"

private:
    uint deform_label(vec3 index) const
    {
        if (!labels_) return 0u;
        const vec3 i = floor(index + 0.5f);
        if (i.x < 0 || i.y < 0 || i.z < 0 || i.x >= float(labels_->size[0]) || i.y >= float(labels_->size[1]) || i.z >= float(labels_->size[2]))
            return 0u;
        const uint code = labels_->as<std::uint8_t>()[labels_->index(std::size_t(i.x), std::size_t(i.y), std::size_t(i.z))];
        return code < uint(DEFORM_TISSUE_CODES) ? code : 0u;
    }
    TissueMechanics deform_tissue(uint code) const { return tissues_[code]; }
    vec2 deform_profile(uint column) const { return {profile_[column].skin_y_mm, profile_[column].skin_shift_mm}; }
    // column-major: one column is walked at a time
    vec4 scratch_load(uint column, uint step) const { return scratch_unpack(scratch_[column * max_steps_ + step]); }
    void scratch_store(uint column, uint step, vec4 v) { scratch_[column * max_steps_ + step] = scratch_pack(v); }
    void map_store(uint pixel, vec2 v) { map_[pixel] = v; }
    float moved_load(uint column, uint boundary) const { return moved_[column * (max_steps_ + 1) + boundary]; }
    void moved_store(uint column, uint boundary, float v) { moved_[column * (max_steps_ + 1) + boundary] = v; }
    vec2 walls_load(uint column, uint boundary) const { return unpackHalf2x16(walls_[column * (max_steps_ + 1) + boundary]); }
    void walls_store(uint column, uint boundary, vec2 v) { walls_[column * (max_steps_ + 1) + boundary] = packHalf2x16(v); }
    // the map spreads in its walk, as a CPU device's kernel does (deform_bindings.h): no spread pass
    static constexpr bool spread_loaded() { return false; }
    float spread_load(uint, uint) const { return 0.0f; }
    void spread_store(uint, uint, float) {}

    const io::Volume* labels_;
    std::span<const ColumnProfile> profile_;
    const TissueTable& tissues_;
    std::vector<uvec2>& scratch_;  // max_steps_ entries a column
    std::size_t max_steps_;
    std::vector<float>& moved_;  // max_steps_ + 1 entries a column
    std::vector<uint>& walls_;   // the same
    std::vector<glm::vec2>& map_;
};

}  // namespace kernels_cpu

std::vector<glm::vec2> deform_cpu(const io::Volume* labels, std::span<const ColumnProfile> profile, const TissueTable& tissues,
                                  const kernels::DeformParams& params)
{
    if (profile.size() != params.columns)
        throw std::invalid_argument("deform: " + std::to_string(profile.size()) + " column profiles for " + std::to_string(params.columns) +
                                    " columns");
    if (labels && labels->type != io::VoxelType::uint8) throw std::invalid_argument("deform: the label map is not uint8");
    std::vector<glm::uvec2> scratch(std::size_t(params.columns) * params.max_steps);
    std::vector<float> moved(std::size_t(params.columns) * (params.max_steps + 1));
    std::vector<std::uint32_t> walls(moved.size());
    std::vector<glm::vec2> map(std::size_t(params.columns) * params.rows);
    kernels_cpu::DeformColumns columns(labels, profile, tissues, scratch, params.max_steps, moved, walls, map);
    // the passes of a CPU device's two dispatches: the map reads the neighbours' solutions
    for (std::uint32_t c = 0; c < params.columns; ++c) columns.deform_column_solve(c, params);
    for (std::uint32_t c = 0; c < params.columns; ++c) columns.deform_column_map(c, params);
    return map;
}

}  // namespace echosim::echo

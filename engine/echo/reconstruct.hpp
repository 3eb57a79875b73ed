// Freehand 3D reconstruction (paper §6): tracked 2D frames pasted into a voxel map, then the holes
// between frames filled by interpolation. Each pixel is splatted into the voxel it falls in
// (nearest) or spread over the eight around it with trilinear weights; where several pixels meet
// one voxel they are compounded by their weighted mean or their maximum. Tissue labels, when the
// frames carry them, are reconstructed alongside (the label of the nearest pixel).
// Hole filling: voxels no pixel reached take the distance-weighted mean of their filled
// neighbours (26-neighbourhood), pass after pass, until none is left within reach of the data
// (max_fill_mm: the gaps between frames of a sweep, not the empty corners of the map's box, which
// stay 0: outside the sweep).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "io/nrrd.hpp"
#include "io/plus_sequence.hpp"

namespace echosim::echo {

enum class Splat { nearest, trilinear };
enum class Compounding { mean, max };

struct ReconstructOptions {
    double voxel_mm = 0.3;
    Splat splat = Splat::trilinear;
    Compounding compounding = Compounding::mean;
    std::uint64_t memory_budget_bytes = std::uint64_t(4) << 30;  // refuse volumes that need more
    double max_fill_mm = 5.0;  // fill holes up to this far from acquired data
};

// The reconstruction's working memory for a box of the given size: what the budget is checked on.
std::uint64_t reconstruction_bytes(const glm::dvec3& box_mm, double voxel_mm);

// The axes of a map aligned with a sweep (the frames' mean lateral and beam directions) and the
// box its frames span in those axes.
struct SweepBox {
    glm::dmat3 axes{1.0};
    glm::dvec3 lo{0.0}, hi{0.0};
};
SweepBox sweep_box(std::span<const glm::dmat4> image_to_world, std::uint32_t width, std::uint32_t height);
// The same for a tracked sweep's frames whose transforms are valid.
SweepBox sweep_box(const io::Sweep& sweep);

class Reconstructor {
public:
    // The voxel map covers the box [lo, hi] of the frame whose orthonormal axes (columns of `axes`)
    // are given in world LPS: a map aligned with the sweep holds far fewer empty voxels than one
    // aligned with the world. Throws std::runtime_error when it would exceed the memory budget,
    // saying how much it needs.
    Reconstructor(const glm::dvec3& lo, const glm::dvec3& hi, const ReconstructOptions& options,
                  const glm::dmat3& axes = glm::dmat3(1.0));

    // One frame: width x height 8-bit pixels, row-major; image_to_world maps (column, row, 0, 1)
    // in pixels to world mm. labels may be empty.
    void insert(std::span<const std::uint8_t> pixels, std::span<const std::uint8_t> labels, std::uint32_t width,
                std::uint32_t height, const glm::dmat4& image_to_world);

    // Fills the holes; returns the passes it took. `progress` (may be empty) gets the fraction done.
    int fill_holes(const std::function<void(double)>& progress = {});

    std::uint64_t filled_voxels() const;  // before or after fill_holes
    std::uint64_t voxel_count() const { return std::uint64_t(size_[0]) * size_[1] * size_[2]; }
    std::uint64_t memory_bytes() const;

    io::Volume volume() const;  // uint8 grey, LPS, with the map's geometry
    io::Volume labels() const;  // uint8 tissue codes (empty voxels: 0)

private:
    std::size_t index(std::size_t i, std::size_t j, std::size_t k) const { return (k * size_[1] + j) * size_[0] + i; }

    ReconstructOptions options_;
    glm::dmat3 axes_;       // the map's axes in world
    glm::dvec3 lo_;         // the box's corner in the map's frame [mm]
    std::array<std::size_t, 3> size_{};
    std::vector<float> value_;   // weighted sum (mean) or maximum
    std::vector<float> weight_;  // 0: a hole
    std::vector<std::uint8_t> label_;
    std::vector<float> label_distance_;  // distance [voxels] of the pixel that set the label
};

}  // namespace echosim::echo

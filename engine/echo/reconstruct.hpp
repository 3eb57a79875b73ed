// Freehand 3D reconstruction (paper §6): tracked 2D frames pasted into a voxel map, then the holes
// between frames filled by interpolation. Each pixel is splatted into the voxel it falls in
// (nearest) or spread over the eight around it with trilinear weights; where several pixels meet
// one voxel they are compounded by their weighted mean or their maximum. Tissue labels, when the
// frames carry them, are reconstructed alongside (the label of the nearest pixel).
// The PLUS toolkit's choices are all here (DESIGN.md §3, issue 12): nearest or trilinear pasting
// (its NEAREST_NEIGHBOR and LINEAR, with its rules at the map's edges), MEAN, MAXIMUM and LATEST
// compounding, a clip rectangle, a pixel rejection threshold, and its output grid (plus_grid);
// 16-bit and float frames keep their values in a float map.
// Hole filling: voxels no pixel reached take the distance-weighted mean of their filled
// neighbours (26-neighbourhood), pass after pass, until none is left within reach of the data
// (max_fill_mm: the gaps between frames of a sweep, not the empty corners of the map's box, which
// stay 0: outside the sweep).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "io/nrrd.hpp"
#include "io/plus_sequence.hpp"

namespace echosim::echo {

enum class Splat { nearest, trilinear };
enum class Compounding { mean, max, latest };

// The pixels of a frame pasted, inclusive, clamped to the frame (PLUS's clip rectangle: its
// ClipRectangleOrigin o and ClipRectangleSize s keep pixels o .. o + s, one more than s).
struct PixelRect {
    std::uint32_t x0 = 0, y0 = 0;
    std::uint32_t x1 = UINT32_MAX, y1 = UINT32_MAX;
};

struct ReconstructOptions {
    double voxel_mm = 0.3;  // the map's spacing when the constructor is given a box
    Splat splat = Splat::trilinear;
    Compounding compounding = Compounding::mean;
    std::uint64_t memory_budget_bytes = std::uint64_t(4) << 30;  // refuse volumes that need more
    double max_fill_mm = 5.0;  // fill holes up to this far from acquired data
    PixelRect clip;            // default: the whole frame
    double pixel_threshold = -1e300;  // pixels whose value is below it are not pasted
    io::VoxelType output_type = io::VoxelType::uint8;  // values rounded and clamped to it
};

// Where the voxels are: voxel (i, j, k) is at axes * (origin + spacing * (i, j, k)) in world.
struct VoxelGrid {
    glm::dmat3 axes{1.0};      // orthonormal columns: the map's axes in world
    glm::dvec3 origin{0.0};    // centre of voxel (0, 0, 0) in the map's axes [mm]
    glm::dvec3 spacing{0.3};   // [mm]
    std::array<std::size_t, 3> size{};

    // The voxels' count; UINT64_MAX when it overflows (a grid no budget takes).
    std::uint64_t voxel_count() const;
};

// The grid over the box [lo, hi] (in the map's axes) at `voxel_mm`, voxel centres on its corners.
VoxelGrid box_grid(const glm::dvec3& lo, const glm::dvec3& hi, double voxel_mm, const glm::dmat3& axes = glm::dmat3(1.0));

// PLUS's output grid (its VolumeReconstructor, SetOutputExtentFromFrameList): axis-aligned in the
// reference frame, over the box of the clipped frames' corner pixels (their centres), with the
// origin on a whole multiple of the spacing: origin = floor(lo / s) * s, last index
// ceil((hi - origin) / s). Throws std::invalid_argument when there is no frame or the spacing is
// not positive.
VoxelGrid plus_grid(std::span<const glm::dmat4> image_to_reference, std::uint32_t width, std::uint32_t height,
                    const PixelRect& clip, const glm::dvec3& spacing);

// What a clip rectangle keeps of a width x height frame (clamped to it); nullopt when it keeps no
// pixel, its origin past the frame's last column or row.
std::optional<PixelRect> clip_to_frame(const PixelRect& clip, std::uint32_t width, std::uint32_t height);

// [mm] How far the corners of the frames' rectangles (`rect`, pixels kept, in every frame) lie from
// the first frame's plane, at most: (almost) 0 when every frame lies in one plane, as when each
// frame's ImageToReference is the same (the identity, say): such a sweep spans no volume.
double sweep_thickness(std::span<const glm::dmat4> image_to_world, const PixelRect& rect);
// [mm] The longest diagonal of a frame's rectangle: what sweep_thickness is judged against.
double frame_diagonal(std::span<const glm::dmat4> image_to_world, const PixelRect& rect);

// Whether any frame's rectangle (`rect`) comes within half a voxel of the grid's box, judged by the
// rectangle's bounding box in the grid's axes: false means no pixel can land in the grid.
bool frames_reach(const VoxelGrid& grid, std::span<const glm::dmat4> image_to_world, const PixelRect& rect);

// The reconstruction's working memory for a grid: what the budget is checked on.
std::uint64_t reconstruction_bytes(const VoxelGrid& grid);
std::uint64_t reconstruction_bytes(const glm::dvec3& box_mm, double voxel_mm);

// One frame's pixels as stored: width x height values of `type`, row-major, little-endian.
struct FramePixels {
    std::span<const std::uint8_t> bytes;
    io::VoxelType type = io::VoxelType::uint8;
    std::uint32_t width = 0, height = 0;
};

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
    // The voxel map on `grid`. Throws std::runtime_error when it would exceed the memory budget,
    // saying how much it needs; std::invalid_argument for an empty grid or a spacing that is not
    // positive.
    Reconstructor(const VoxelGrid& grid, const ReconstructOptions& options);
    // The map over the box [lo, hi] of the frame whose orthonormal axes (columns of `axes`) are
    // given in world LPS, at options.voxel_mm: a map aligned with the sweep holds far fewer empty
    // voxels than one aligned with the world.
    Reconstructor(const glm::dvec3& lo, const glm::dvec3& hi, const ReconstructOptions& options,
                  const glm::dmat3& axes = glm::dmat3(1.0));

    // One frame; image_to_world maps (column, row, 0, 1) in pixels to world mm. labels (one byte a
    // pixel) may be empty.
    void insert(const FramePixels& frame, std::span<const std::uint8_t> labels, const glm::dmat4& image_to_world);
    // The same for 8-bit pixels.
    void insert(std::span<const std::uint8_t> pixels, std::span<const std::uint8_t> labels, std::uint32_t width,
                std::uint32_t height, const glm::dmat4& image_to_world)
    {
        insert(FramePixels{pixels, io::VoxelType::uint8, width, height}, labels, image_to_world);
    }

    // Fills the holes; returns the passes it took. `progress` (may be empty) gets the fraction done.
    int fill_holes(const std::function<void(double)>& progress = {});

    std::uint64_t filled_voxels() const;  // before or after fill_holes
    std::uint64_t voxel_count() const { return std::uint64_t(size_[0]) * size_[1] * size_[2]; }
    std::uint64_t memory_bytes() const;

    const VoxelGrid& grid() const { return grid_; }

    io::Volume volume() const;  // options.output_type grey, LPS, with the map's geometry
    io::Volume labels() const;  // uint8 tissue codes (empty voxels: 0)

private:
    std::size_t index(std::size_t i, std::size_t j, std::size_t k) const { return (k * size_[1] + j) * size_[0] + i; }
    io::Volume empty_volume(io::VoxelType type) const;

    ReconstructOptions options_;
    VoxelGrid grid_;
    std::array<std::size_t, 3> size_{};
    std::vector<float> row_;     // one row of the frame being pasted, as float
    std::vector<float> value_;   // weighted sum (mean) or maximum
    std::vector<float> weight_;  // 0: a hole
    std::vector<std::uint8_t> label_;
    std::vector<float> label_distance_;  // distance [voxels] of the pixel that set the label
};

}  // namespace echosim::echo

// The patch as the solver stages see it: a rows x cols grid of nodes (row-major) whose every node
// has a spring to its east, south, south-east and south-west neighbour where the grid has one
// (tissue/tissue_model.hpp builds exactly these). Per-spring data live in planes, one per
// direction and quantity, indexed by the spring's first node, so the stages run as straight loops
// over contiguous memory that the compiler vectorises. Each plane is preceded by cols + 1 zeros:
// the spring that reaches node i in a direction can then be read at i - offset for every i (zero
// for the first row), without a branch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/fork_join.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

enum SpringDirection : int { kEast = 0, kSouth = 1, kSouthEast = 2, kSouthWest = 3 };
inline constexpr int kSpringDirections = 4;

struct GridLayout {
    int rows = 0, cols = 0;
    std::size_t n = 0;
    // each model spring's direction and first node, in the model's order
    std::vector<std::uint8_t> spring_direction;
    std::vector<std::uint32_t> spring_first;

    // index distance from a spring's first node to its second
    std::size_t offset(int direction) const
    {
        return direction == kEast ? 1 : direction == kSouth ? std::size_t(cols) : direction == kSouthEast ? std::size_t(cols + 1)
                                                                                                             : std::size_t(cols - 1);
    }
};

// Throws std::invalid_argument if the model's springs are not the grid's (each direction once).
GridLayout make_grid_layout(const tissue::TissueModel& model);

// What part `part` of a team of `parts` takes of the grid: whole rows, as [first, end) rows or as
// the nodes of those rows. Every pass of a step splits this way, so a part keeps to the same data
// (and its core's caches) from pass to pass.
inline std::pair<std::size_t, std::size_t> part_rows(const GridLayout& g, int part, int parts)
{
    return part_range(std::size_t(g.rows), part, parts);
}
inline std::pair<std::size_t, std::size_t> part_nodes(const GridLayout& g, int part, int parts)
{
    const auto [first, end] = part_rows(g, part, parts);
    return {first * std::size_t(g.cols), end * std::size_t(g.cols)};
}

// `components` planes per direction (e.g. iso, w.x, w.y, w.z), zero-padded as above.
struct SpringPlanes {
    int components = 0;
    std::size_t stride = 0;  // n + cols + 1
    std::size_t pad = 0;     // cols + 1
    std::vector<float> data;

    float* plane(int direction, int component) { return data.data() + std::size_t(components * direction + component) * stride + pad; }
    const float* plane(int direction, int component) const
    {
        return data.data() + std::size_t(components * direction + component) * stride + pad;
    }
};

SpringPlanes make_spring_planes(const GridLayout& layout, int components);

// Plane vectors: 3n values, all x, then all y, then all z. Conversions of nodes [begin, end) (by
// default all) to and from the state's interleaved doubles (node i at 3i..3i+2).
void to_planes(const double* interleaved, std::size_t n, float* planes, std::size_t begin = 0, std::size_t end = SIZE_MAX);
void to_planes(const double* interleaved, std::size_t n, double* planes, std::size_t begin = 0, std::size_t end = SIZE_MAX);
void add_planes_to(const float* planes, std::size_t n, double* interleaved, std::size_t begin = 0, std::size_t end = SIZE_MAX);

}  // namespace echosim::physics

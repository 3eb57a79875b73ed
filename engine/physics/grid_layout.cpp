#include "physics/grid_layout.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace echosim::physics {

GridLayout make_grid_layout(const tissue::TissueModel& model)
{
    GridLayout g;
    g.rows = model.rows;
    g.cols = model.cols;
    g.n = model.node_count();
    if (g.rows < 2 || g.cols < 2 || g.n != std::size_t(g.rows) * std::size_t(g.cols))
        throw std::invalid_argument("tissue model: " + std::to_string(g.n) + " nodes do not make a " + std::to_string(g.rows) + " x " +
                                    std::to_string(g.cols) + " grid");
    std::vector<std::uint8_t> taken(std::size_t(kSpringDirections) * g.n, 0);
    for (const tissue::Spring& sp : model.springs) {
        if (sp.i >= g.n || sp.j >= g.n)
            throw std::invalid_argument("tissue model: spring " + std::to_string(sp.i) + "-" + std::to_string(sp.j) + " names a node beyond the " +
                                        std::to_string(g.n) + " nodes");
        const int ri = int(sp.i) / g.cols, ci = int(sp.i) % g.cols, rj = int(sp.j) / g.cols, cj = int(sp.j) % g.cols;
        // a spring's blocks read the same from either end, so each goes to its upper (or western) node
        const bool forward = rj > ri || (rj == ri && cj > ci);
        const int dr = forward ? rj - ri : ri - rj, dc = forward ? cj - ci : ci - cj;
        const std::uint32_t first = forward ? sp.i : sp.j;
        int direction = -1;
        if (dr == 0 && dc == 1) direction = kEast;
        if (dr == 1 && dc == 0) direction = kSouth;
        if (dr == 1 && dc == 1) direction = kSouthEast;
        if (dr == 1 && dc == -1) direction = kSouthWest;
        if (direction < 0 || taken[std::size_t(direction) * g.n + first])
            throw std::invalid_argument("tissue model: spring " + std::to_string(sp.i) + "-" + std::to_string(sp.j) +
                                        " is not one of the grid's (east, south, south-east, south-west, once each)");
        taken[std::size_t(direction) * g.n + first] = 1;
        g.spring_direction.push_back(std::uint8_t(direction));
        g.spring_first.push_back(first);
    }
    return g;
}

SpringPlanes make_spring_planes(const GridLayout& layout, int components)
{
    SpringPlanes p;
    p.components = components;
    p.pad = std::size_t(layout.cols + 1);
    p.stride = layout.n + p.pad;
    p.data.assign(std::size_t(components * kSpringDirections) * p.stride, 0.0f);
    return p;
}

namespace {

template <class T>
void interleaved_to_planes(const double* interleaved, std::size_t n, T* planes, std::size_t begin, std::size_t end)
{
    for (std::size_t i = begin; i < std::min(end, n); ++i)
        for (std::size_t c = 0; c < 3; ++c) planes[c * n + i] = T(interleaved[3 * i + c]);
}

}  // namespace

void to_planes(const double* interleaved, std::size_t n, float* planes, std::size_t begin, std::size_t end)
{
    interleaved_to_planes(interleaved, n, planes, begin, end);
}

void to_planes(const double* interleaved, std::size_t n, double* planes, std::size_t begin, std::size_t end)
{
    interleaved_to_planes(interleaved, n, planes, begin, end);
}

void add_planes_to(const float* planes, std::size_t n, double* interleaved, std::size_t begin, std::size_t end)
{
    for (std::size_t i = begin; i < std::min(end, n); ++i)
        for (std::size_t c = 0; c < 3; ++c) interleaved[3 * i + c] += double(planes[c * n + i]);
}

}  // namespace echosim::physics

#include "bench/slice_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "core/fork_join.hpp"
#include "echo/phantom.hpp"
#include "session/session.hpp"

namespace echosim::bench {
namespace {

constexpr std::array<double, 3> kBoxMm = {40.0, 60.0, 120.0};  // lateral, beam, elevation
// where the box's centre lies along the resting probe's beam [mm]: from 2 mm above the skin down
// to 58 mm, so the image of the probe pressed 12 mm in (12 to 62 mm) lies in it but for its foot
constexpr double kCentreDepthMm = 28.0;
constexpr double kPressMm = 12.0;

// The continuous index of a grid's centre.
glm::dvec3 middle(const std::array<std::size_t, 3>& n)
{
    return (glm::dvec3{double(n[0]), double(n[1]), double(n[2])} - 1.0) * 0.5;
}

// The box's grid at `voxel_mm`: the resting probe's axes turned 4 deg about the beam and 3 deg
// about the array, centred on the beam.
io::Volume grid(const Pose& rest, double voxel_mm, std::array<std::size_t, 3> size)
{
    const glm::quat turn = glm::angleAxis(glm::radians(4.0f), rest.axis_y()) * glm::angleAxis(glm::radians(3.0f), rest.axis_x());
    const glm::dmat3 axes(glm::mat3_cast(turn * rest.orientation));
    io::Volume v = io::make_volume(size, io::VoxelType::uint8);
    v.directions = axes * voxel_mm;
    const glm::dvec3 centre = glm::dvec3(rest.position) + kCentreDepthMm * glm::dvec3(rest.axis_y());
    v.origin = centre - v.directions * middle(size);
    return v;
}

std::array<std::size_t, 3> grid_size(double voxel_mm)
{
    std::array<std::size_t, 3> n{};
    for (int a = 0; a < 3; ++a) n[std::size_t(a)] = std::size_t(std::lround(kBoxMm[std::size_t(a)] / voxel_mm));
    return n;
}

// xorshift64, eight voxels a step: speckle at memory speed (a second for 288 M voxels)
void fill_speckle(io::Volume& v, std::uint64_t seed)
{
    std::uint64_t x = seed;
    const std::size_t words = v.data.size() / 8;
    auto* out = reinterpret_cast<std::uint64_t*>(v.data.data());
    for (std::size_t i = 0; i < words; ++i) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        out[i] = x;
    }
    for (std::size_t i = words * 8; i < v.data.size(); ++i) v.data[i] = std::uint8_t(i);
}

}  // namespace

SliceVolume make_coarse_volume()
{
    const session::Session s;
    const echo::Phantom phantom(s.leg(), echo::Case::healthy);
    SliceVolume out{0.3, grid(s.probe().rest, 0.3, grid_size(0.3)), {}};
    out.labels = out.grey;
    fill_speckle(out.grey, 0x9e3779b97f4a7c15ull);
    // the phantom per voxel, elevation slabs shared among the cores (10.7 M voxels)
    io::Volume& l = out.labels;
    ForkJoin team(int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(ForkJoin::kMaxParts))));
    team.run([&](int part) {
        const auto [k0, k1] = part_range(l.size[2], part, team.parts());
        for (std::size_t k = k0; k < k1; ++k)
            for (std::size_t j = 0; j < l.size[1]; ++j)
                for (std::size_t i = 0; i < l.size[0]; ++i)
                    l.data[l.index(i, j, k)] = std::uint8_t(phantom.tissue_at(l.index_to_world(glm::dvec3(double(i), double(j), double(k)))));
    });
    return out;
}

SliceVolume make_fine_volume(const SliceVolume& coarse)
{
    const glm::dvec3 step(glm::length(coarse.grey.directions[0]), glm::length(coarse.grey.directions[1]),
                          glm::length(coarse.grey.directions[2]));
    const glm::dmat3 axes(coarse.grey.directions[0] / step.x, coarse.grey.directions[1] / step.y, coarse.grey.directions[2] / step.z);
    const std::array<std::size_t, 3> size = grid_size(0.1);
    SliceVolume out{0.1, io::make_volume(size, io::VoxelType::uint8), {}};
    out.grey.directions = axes * 0.1;
    // the same box, the same centre
    out.grey.origin = coarse.grey.index_to_world(middle(coarse.grey.size)) - out.grey.directions * middle(size);
    out.labels = out.grey;
    fill_speckle(out.grey, 0xbf58476d1ce4e5b9ull);
    // nearest coarse voxel, axis by axis (the grids share their axes)
    std::array<std::vector<std::size_t>, 3> nearest;
    for (std::size_t a = 0; a < 3; ++a) {
        const double fine_centre = (double(size[a]) - 1.0) * 0.5, coarse_centre = (double(coarse.labels.size[a]) - 1.0) * 0.5;
        for (std::size_t i = 0; i < size[a]; ++i) {
            const double c = std::round((double(i) - fine_centre) * 0.1 / step[int(a)] + coarse_centre);
            nearest[a].push_back(std::size_t(std::clamp(c, 0.0, double(coarse.labels.size[a] - 1))));
        }
    }
    io::Volume& l = out.labels;
    for (std::size_t k = 0; k < size[2]; ++k)
        for (std::size_t j = 0; j < size[1]; ++j) {
            const std::uint8_t* row = &coarse.labels.data[coarse.labels.index(0, nearest[1][j], nearest[2][k])];
            std::uint8_t* dst = &l.data[l.index(0, j, k)];
            for (std::size_t i = 0; i < size[0]; ++i) dst[i] = row[nearest[0][i]];
        }
    return out;
}

echo::EchoFrame pressed_frame(const echo::ImagePlane& plane)
{
    session::Session s(session::SessionOptions{.image = plane});
    s.press_and_settle(s.probe().rest, kPressMm);
    return *s.view().echo;
}

}  // namespace echosim::bench

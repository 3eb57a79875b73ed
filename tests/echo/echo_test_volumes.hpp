// Volumes for the echographic image's tests: the phantom's tissue labels on a grid around the
// session's default probe (the patch centre, over the femoral vessels), with grey levels that
// follow the tissue plus a fixed speckle, so the tests can measure vessels from the labels the
// pipeline outputs and compare images. The grid is the probe's rest frame turned a few degrees, so
// the image plane cuts it obliquely, as a reconstructed volume's grid would be.
#pragma once

#include <cstdint>

#include <glm/gtc/quaternion.hpp>

#include "echo/phantom.hpp"
#include "io/nrrd.hpp"
#include "scene/leg.hpp"
#include "session/session.hpp"

namespace echosim::test {

struct LabelledVolume {
    io::Volume grey;
    io::Volume labels;
};

inline LabelledVolume phantom_volume(const scene::LegModel& leg, echo::Case which, const Pose& probe_rest, double voxel_mm = 0.3)
{
    const echo::Phantom phantom(leg, which);
    // x lateral -24..24 mm, y along the beam -30..56 mm (a pressed probe looks up to 25 mm above its
    // face), z elevation -4..4 mm, in the probe's frame turned 3 degrees about its beam
    const glm::dquat turn = glm::angleAxis(glm::radians(3.0), glm::dvec3(0, 1, 0));
    const glm::dmat3 axes = glm::dmat3(glm::mat3_cast(glm::dquat(probe_rest.orientation) * turn));
    const glm::dvec3 lo(-24, -30, -4), hi(24, 56, 4);
    const std::array<std::size_t, 3> size{std::size_t((hi.x - lo.x) / voxel_mm) + 1, std::size_t((hi.y - lo.y) / voxel_mm) + 1,
                                          std::size_t((hi.z - lo.z) / voxel_mm) + 1};
    LabelledVolume v{io::make_volume(size, io::VoxelType::uint8), io::make_volume(size, io::VoxelType::uint8)};
    for (io::Volume* x : {&v.grey, &v.labels}) {
        x->directions = axes * voxel_mm;
        x->origin = glm::dvec3(probe_rest.position) + axes * lo;
    }
    std::uint8_t* g = v.grey.as<std::uint8_t>();
    std::uint8_t* l = v.labels.as<std::uint8_t>();
    for (std::size_t k = 0; k < size[2]; ++k)
        for (std::size_t j = 0; j < size[1]; ++j)
            for (std::size_t i = 0; i < size[0]; ++i) {
                const std::size_t at = v.grey.index(i, j, k);
                const auto t = phantom.tissue_at(v.labels.index_to_world(glm::dvec3(double(i), double(j), double(k))));
                l[at] = std::uint8_t(t);
                const std::uint32_t hash = std::uint32_t(at * 2654435761u) >> 24;  // a fixed speckle, 0..255
                g[at] = std::uint8_t(t == echo::Tissue::outside ? 0 : 40 + (std::uint32_t(t) * 13 + hash) % 200);
            }
    return v;
}

// The session's echographic frames at its probe's rest pose: at rest (no deform: the columns
// cleared) and pressed `press_mm` and settled (the session is left so).
struct RestAndPressed {
    echo::EchoFrame rest, pressed;
};
inline RestAndPressed rest_and_pressed(session::Session& s, double press_mm)
{
    RestAndPressed f{*s.view().echo, {}};
    f.rest.columns.clear();
    s.press_and_settle(s.probe().rest, press_mm);
    f.pressed = *s.view().echo;
    return f;
}

}  // namespace echosim::test

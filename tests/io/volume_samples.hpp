// Volumes shared by the tests of the volume formats (NRRD, MetaImage): one that exercises geometry
// and every voxel.
#pragma once

#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "io/nrrd.hpp"

namespace echosim::test {

// An oblique 5 x 4 x 3 volume: rotated about two axes, anisotropic voxels, an origin no short
// decimal writes, every voxel different (negative ones for the signed types, a -0 among floats),
// and one key/value.
inline io::Volume oblique_volume(io::VoxelType type)
{
    io::Volume v = io::make_volume({5, 4, 3}, type);
    const glm::dmat4 rotation = glm::rotate(glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(0, 0, 1)), -0.25, glm::dvec3(1, 0, 0));
    v.directions = glm::dmat3(rotation) * glm::dmat3(glm::dvec3(0.3, 0, 0), glm::dvec3(0, 0.45, 0), glm::dvec3(0, 0, 1.7));
    v.origin = {-12.5, 101.25, -3.0 / 7.0};
    v.key_values["Segment0_Name"] = "femoral vein";
    for (std::size_t i = 0; i < v.voxel_count(); ++i) {
        switch (type) {
        case io::VoxelType::uint8: v.as<std::uint8_t>()[i] = std::uint8_t(i * 37 + 5); break;
        case io::VoxelType::uint16: v.as<std::uint16_t>()[i] = std::uint16_t(i * 997 + 3); break;
        case io::VoxelType::int16: v.as<std::int16_t>()[i] = std::int16_t(int(i) * 541 - 20000); break;
        case io::VoxelType::float32: v.as<float>()[i] = float(i) * 0.125f - 3.0f; break;
        }
    }
    if (type == io::VoxelType::float32) v.as<float>()[7] = -0.0f;
    return v;
}

}  // namespace echosim::test

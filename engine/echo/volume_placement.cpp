#include "echo/volume_placement.hpp"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace echosim::echo {

double plane_coverage(const io::Volume& volume, const ImagePlane& plane, const Pose& face)
{
    const glm::dmat4 to_world = pixel_to_world(plane, face);
    const glm::dmat3 to_index = glm::inverse(volume.directions);
    const std::uint32_t across = std::min(plane.columns, 64u), down = std::min(plane.rows, 64u);
    int inside = 0;
    for (std::uint32_t j = 0; j < down; ++j)
        for (std::uint32_t i = 0; i < across; ++i) {
            // pixel centres spread evenly over the image, its corners included
            const double c = across > 1 ? double(i) * (plane.columns - 1) / (across - 1) : 0.0;
            const double r = down > 1 ? double(j) * (plane.rows - 1) / (down - 1) : 0.0;
            const glm::dvec3 ijk = to_index * (glm::dvec3(to_world * glm::dvec4(c, r, 0.0, 1.0)) - volume.origin);
            bool in = true;
            for (int a = 0; a < 3; ++a) in = in && ijk[a] >= -0.5 && ijk[a] <= double(volume.size[std::size_t(a)]) - 0.5;
            inside += in;
        }
    return double(inside) / (double(across) * down);
}

Pose pose_on_volume(const io::Volume& volume)
{
    const glm::dvec3 middle((double(volume.size[0]) - 1) / 2, -0.5, (double(volume.size[2]) - 1) / 2);
    const glm::dvec3 face = volume.index_to_world(middle);
    return pose_from_axes(glm::vec3(face), glm::vec3(glm::normalize(volume.directions[0])), glm::vec3(glm::normalize(volume.directions[1])));
}

}  // namespace echosim::echo

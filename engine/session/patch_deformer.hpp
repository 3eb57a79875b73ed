// Carries the tissue model's node displacements onto the render patch. The tissue grid covers the
// sample area of the patch (u, v in [1/16, 15/16]); each render vertex inside it follows the
// bilinear interpolation of its cell's four nodes, vertices outside stay at rest (the tissue grid's
// rim is fixed, so the two meet without a step). Normals are recomputed from the deformed mesh.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scene/leg.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::session {

class PatchDeformer {
public:
    PatchDeformer(const scene::LegModel& leg, const tissue::TissueModel& model);

    // `positions`: 3 per tissue node [mm]; `patch`: the render patch, rewritten from its rest shape.
    // Throws std::invalid_argument when `positions` is not 3 per node of the model it was made for.
    void apply(std::span<const float> positions, std::vector<scene::Vertex>& patch) const;

private:
    struct Weights {
        std::array<std::uint32_t, 4> nodes{};
        std::array<float, 4> w{};
        bool inside = false;
    };
    const scene::Mesh& rest_;
    std::vector<glm::vec3> tissue_rest_;
    std::vector<Weights> weights_;
    mutable scene::Mesh scratch_;
};

}  // namespace echosim::session

#include "session/patch_deformer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace echosim::session {

PatchDeformer::PatchDeformer(const scene::LegModel& leg, const tissue::TissueModel& model) : rest_(leg.patch().rest)
{
    using tissue::SampleGrid;
    for (const auto& p : model.positions) tissue_rest_.push_back(glm::vec3(p));
    const auto& patch = leg.patch();
    const double u0 = SampleGrid::u(0), u1 = SampleGrid::u(SampleGrid::rows - 1);
    const double v0 = SampleGrid::v(0), v1 = SampleGrid::v(SampleGrid::cols - 1);
    for (int i = 0; i < patch.rows; ++i)
        for (int j = 0; j < patch.cols; ++j) {
            const double u = double(i) / (patch.rows - 1), v = double(j) / (patch.cols - 1);
            Weights w;
            // position in the tissue grid's cells
            const double gr = (u - u0) / (u1 - u0) * (model.rows - 1), gc = (v - v0) / (v1 - v0) * (model.cols - 1);
            if (gr >= 0 && gc >= 0 && gr <= model.rows - 1 && gc <= model.cols - 1) {
                const int r = std::min(int(gr), model.rows - 2), c = std::min(int(gc), model.cols - 2);
                const float tr = float(gr - r), tc = float(gc - c);
                w.nodes = {model.node(r, c), model.node(r, c + 1), model.node(r + 1, c), model.node(r + 1, c + 1)};
                w.w = {(1 - tr) * (1 - tc), (1 - tr) * tc, tr * (1 - tc), tr * tc};
                w.inside = true;
            }
            weights_.push_back(w);
        }
    scratch_ = rest_;
}

void PatchDeformer::apply(std::span<const float> positions, std::vector<scene::Vertex>& patch) const
{
    if (positions.size() != 3 * tissue_rest_.size())
        throw std::invalid_argument("patch deformer: " + std::to_string(positions.size()) + " coordinates for a tissue of " +
                                    std::to_string(tissue_rest_.size()) + " nodes");
    for (std::size_t k = 0; k < weights_.size(); ++k) {
        scratch_.vertices[k] = rest_.vertices[k];
        const Weights& w = weights_[k];
        if (!w.inside) continue;
        glm::vec3 d(0.0f);
        for (int q = 0; q < 4; ++q) {
            const std::uint32_t n = w.nodes[std::size_t(q)];
            d += w.w[std::size_t(q)] * (glm::vec3(positions[3 * n], positions[3 * n + 1], positions[3 * n + 2]) - tissue_rest_[n]);
        }
        scratch_.vertices[k].position += d;
    }
    scene::recompute_normals(scratch_);
    patch = scratch_.vertices;
}

}  // namespace echosim::session

#include "tissue/tissue_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>


namespace echosim::tissue {

TissueModel build_tissue_model(const SkinSurface& skin, const SampleParameters& params, int refine)
{
    if (refine < 1 || refine > 64) throw std::invalid_argument("tissue model refinement " + std::to_string(refine) + " outside 1..64");
    TissueModel m;
    m.refine = refine;
    m.rows = (SampleGrid::rows - 1) * refine + 1;
    m.cols = (SampleGrid::cols - 1) * refine + 1;
    m.lambda = params.lambda;
    // mu is not fitted but set for a damping ratio of one node's mass on its stiffness (fit.cpp);
    // both scale by 1/r^2 with refinement, and so does mu. (lambda does not: a 2-D spring network's
    // membrane stiffness is the same at any spacing.)
    m.mu = params.mu / (double(refine) * double(refine));
    m.samples = params;
    const std::size_t n = std::size_t(m.rows) * std::size_t(m.cols);
    m.positions.resize(n);
    m.normals.resize(n);
    m.a.resize(n);
    m.b.resize(n);
    m.mass.resize(n);
    m.boundary.resize(n);

    const double u0 = SampleGrid::u(0), u1 = SampleGrid::u(SampleGrid::rows - 1);
    const double v0 = SampleGrid::v(0), v1 = SampleGrid::v(SampleGrid::cols - 1);
    const double scale = double(refine) * double(refine);
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c) {
            const std::uint32_t k = m.node(r, c);
            const double u = u0 + (u1 - u0) * r / (m.rows - 1), v = v0 + (v1 - v0) * c / (m.cols - 1);
            m.positions[k] = glm::dvec3(skin.patch_point(float(u), float(v)));
            m.normals[k] = glm::normalize(glm::dvec3(skin.patch_normal(float(u), float(v))));
            m.boundary[k] = r == 0 || c == 0 || r == m.rows - 1 || c == m.cols - 1;

            // bilinear interpolation between the four surrounding sample points, in 1/b and b/a
            const double fr = double(r) / refine, fc = double(c) / refine;
            const int r0 = std::min(int(fr), SampleGrid::rows - 2), c0 = std::min(int(fc), SampleGrid::cols - 2);
            const double tr = fr - r0, tc = fc - c0;
            double stiffness = 0, limit = 0;
            for (int dr = 0; dr < 2; ++dr)
                for (int dc = 0; dc < 2; ++dc) {
                    const double w = (dr ? tr : 1 - tr) * (dc ? tc : 1 - tc);
                    const int p = SampleGrid::index(r0 + dr, c0 + dc);
                    stiffness += w / params.b[std::size_t(p)];
                    limit += w * (params.a[std::size_t(p)] > 0 ? params.b[std::size_t(p)] / params.a[std::size_t(p)] : 1e6);
                }
            m.b[k] = scale / stiffness;
            m.a[k] = m.b[k] / limit;
        }

    // springs: structural along both grid directions, shear along both diagonals
    auto add = [&](int r0, int c0, int r1, int c1) {
        if (r1 < 0 || c1 < 0 || r1 >= m.rows || c1 >= m.cols) return;
        const std::uint32_t i = m.node(r0, c0), j = m.node(r1, c1);
        m.springs.push_back({i, j, glm::length(m.positions[i] - m.positions[j])});
    };
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c) {
            add(r, c, r, c + 1);
            add(r, c, r + 1, c);
            add(r, c, r + 1, c + 1);
            add(r, c, r + 1, c - 1);
        }

    // each node's mass: its share of the patch area (a quarter of each neighbouring grid cell)
    for (int r = 0; r + 1 < m.rows; ++r)
        for (int c = 0; c + 1 < m.cols; ++c) {
            const auto& p00 = m.positions[m.node(r, c)];
            const double area = glm::length(glm::cross(m.positions[m.node(r + 1, c)] - p00, m.positions[m.node(r, c + 1)] - p00));
            for (auto k : {m.node(r, c), m.node(r + 1, c), m.node(r, c + 1), m.node(r + 1, c + 1)})
                m.mass[k] += 0.25 * area * kSurfaceMassPerArea;
        }
    return m;
}

}  // namespace echosim::tissue

#include "session/patch_deformer.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "scene/leg.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::session {
namespace {

// A small tissue grid (refine 2: 15 x 15 nodes) whose parameters do not matter here: the deformer
// reads only its layout and rest positions.
tissue::TissueModel small_model(const scene::LegModel& leg)
{
    tissue::SampleParameters p;
    p.a.fill(0.01);
    p.b.fill(2.0);
    p.lambda = 1e-3;
    return tissue::build_tissue_model(leg, p, 2);
}

// Where render vertex (i, j) of the patch lies in the tissue grid's (row, column) coordinates, or
// false when it lies outside the tissue grid: the patch spans u, v in [0, 1], the tissue grid the
// sample points' span [u(0), u(7)] (tissue/sample_grid.hpp).
bool grid_coordinates(const scene::ExamPatch& patch, const tissue::TissueModel& m, int i, int j, double& gr, double& gc)
{
    const double u = double(i) / (patch.rows - 1), v = double(j) / (patch.cols - 1);
    const double lo = 0.5 / 8, hi = 7.5 / 8;
    gr = (u - lo) / (hi - lo) * (m.rows - 1);
    gc = (v - lo) / (hi - lo) * (m.cols - 1);
    const double eps = 1e-9;
    return gr >= -eps && gc >= -eps && gr <= m.rows - 1 + eps && gc <= m.cols - 1 + eps;
}

TEST(PatchDeformer, TissueAtRestLeavesThePatchAtRest)
{
    const scene::LegModel leg;
    const tissue::TissueModel m = small_model(leg);
    const PatchDeformer deformer(leg, m);
    std::vector<float> positions;
    for (const auto& p : m.positions)
        for (int c = 0; c < 3; ++c) positions.push_back(float(p[c]));
    std::vector<scene::Vertex> patch;
    deformer.apply(positions, patch);
    const auto& rest = leg.patch().rest.vertices;
    ASSERT_EQ(patch.size(), rest.size());
    for (std::size_t k = 0; k < rest.size(); ++k) EXPECT_LT(glm::length(patch[k].position - rest[k].position), 1e-3f) << k;
}

// Bilinear interpolation reproduces a displacement linear in the grid's coordinates exactly, so every
// render vertex over the tissue grid moves by that field at its place, and the rim beyond stays put.
TEST(PatchDeformer, CarriesALinearDisplacementFieldOntoThePatch)
{
    const scene::LegModel leg;
    const tissue::TissueModel m = small_model(leg);
    const PatchDeformer deformer(leg, m);
    const glm::dvec3 per_row(0.0, 0.4, 0.1), per_col(-0.2, 0.3, 0.0);  // [mm per grid step]
    std::vector<float> positions;
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < m.cols; ++c) {
            const glm::dvec3 p = m.positions[m.node(r, c)] + double(r) * per_row + double(c) * per_col;
            for (int k = 0; k < 3; ++k) positions.push_back(float(p[k]));
        }
    std::vector<scene::Vertex> patch;
    deformer.apply(positions, patch);

    const scene::ExamPatch& ep = leg.patch();
    int inside = 0, outside = 0;
    for (int i = 0; i < ep.rows; ++i)
        for (int j = 0; j < ep.cols; ++j) {
            const std::size_t k = std::size_t(i * ep.cols + j);
            const glm::vec3 moved = patch[k].position - ep.rest.vertices[k].position;
            double gr = 0, gc = 0;
            if (grid_coordinates(ep, m, i, j, gr, gc)) {
                const glm::vec3 expected(gr * per_row + gc * per_col);
                EXPECT_LT(glm::length(moved - expected), 2e-3f) << "vertex " << i << "," << j;
                ++inside;
            } else {
                EXPECT_EQ(moved, glm::vec3(0.0f)) << "vertex " << i << "," << j << " is off the tissue grid";
                ++outside;
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 10);
}

TEST(PatchDeformer, NormalsFollowTheDeformedSurface)
{
    const scene::LegModel leg;
    const tissue::TissueModel m = small_model(leg);
    const PatchDeformer deformer(leg, m);
    // push the centre node 8 mm in along its normal: the patch around it tilts towards it
    std::vector<float> positions;
    const std::uint32_t centre = m.node(m.rows / 2, m.cols / 2);
    for (std::size_t n = 0; n < m.node_count(); ++n) {
        const glm::dvec3 p = m.positions[n] - (n == centre ? 8.0 * m.normals[n] : glm::dvec3(0.0));
        for (int c = 0; c < 3; ++c) positions.push_back(float(p[c]));
    }
    std::vector<scene::Vertex> patch;
    deformer.apply(positions, patch);
    const auto& rest = leg.patch().rest.vertices;
    // the vertex nearest the pushed node moved in by about 8 mm; its normal still points outward
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < rest.size(); ++k)
        if (glm::length(rest[k].position - glm::vec3(m.positions[centre])) < glm::length(rest[nearest].position - glm::vec3(m.positions[centre])))
            nearest = k;
    EXPECT_NEAR(glm::dot(patch[nearest].position - rest[nearest].position, -glm::vec3(m.normals[centre])), 8.0f, 0.5f);
    EXPECT_GT(glm::dot(patch[nearest].normal, rest[nearest].normal), 0.9f);
    // on the slope of the dent the normal leans towards the dent's centre
    int tilted = 0;
    for (std::size_t k = 0; k < rest.size(); ++k) {
        const glm::vec3 to_centre = glm::vec3(m.positions[centre]) - rest[k].position;
        const float d = glm::length(to_centre);
        if (d > 3.0f && d < 8.0f) tilted += glm::dot(patch[k].normal - rest[k].normal, to_centre) > 0.0f ? 1 : -1;
    }
    EXPECT_GT(tilted, 0);
}

}  // namespace
}  // namespace echosim::session

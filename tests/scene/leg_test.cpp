#include "scene/leg.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim::scene {
namespace {

TEST(LegModel, PatchBorderCoincidesWithTheLeg)
{
    const LegModel leg;
    const ExamPatch& p = leg.patch();
    ASSERT_GT(p.rows, 8);
    ASSERT_GT(p.cols, 8);
    ASSERT_EQ(p.rest.vertices.size(), std::size_t(p.rows * p.cols));
    // every corner of the patch is a vertex of the static leg mesh (the hole's corner)
    for (int corner : {0, p.cols - 1, (p.rows - 1) * p.cols, p.rows * p.cols - 1}) {
        const glm::vec3 c = p.rest.vertices[std::size_t(corner)].position;
        float nearest = 1e9f;
        for (const auto& v : leg.static_mesh().vertices) nearest = std::min(nearest, glm::length(v.position - c));
        EXPECT_LT(nearest, 1e-3f) << "corner " << corner;
    }
}

TEST(LegModel, PatchSitsOnTheAnteriorMedialProximalThigh)
{
    const LegModel leg;
    const Bounds b = bounds(leg.patch().rest);
    const glm::vec3 size = b.max - b.min;
    // about 120 mm along the thigh, below the groin (z = 0) and above mid-thigh
    EXPECT_NEAR(size.z, 120.0f, 12.0f);
    EXPECT_LT(b.max.z, 0.0f);
    EXPECT_GT(b.min.z, -250.0f);
    // right leg (x < 0 in LPS), facing anterior (-y) and medial (+x)
    const Pose centre = leg.probe_rest_pose(0.5f, 0.5f);
    EXPECT_LT(centre.position.x, 0.0f);
    const glm::vec3 outward = -centre.axis_y();
    EXPECT_LT(outward.y, -0.4f);
    EXPECT_GT(outward.x, 0.3f);
}

TEST(LegModel, ProbeRestPoseTouchesTheSkinTransversely)
{
    const LegModel leg;
    const ExamPatch& p = leg.patch();
    const Pose pose = leg.probe_rest_pose(0.0f, 0.0f);
    // the probe origin is the patch's first vertex, the beam goes into the limb
    EXPECT_LT(glm::length(pose.position - p.rest.vertices[0].position), 1e-3f);
    EXPECT_NEAR(glm::dot(pose.axis_y(), p.rest.vertices[0].normal), -1.0f, 1e-3f);
    // transverse: the elevation axis runs along the thigh (mostly z)
    EXPECT_GT(std::abs(pose.axis_z().z), 0.9f);
}

TEST(LinearProbe, FaceIs40By10Millimetres)
{
    const Mesh probe = make_linear_probe();
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const auto& v : probe.vertices)
        if (std::abs(v.position.y) < 1e-4f) {
            lo = glm::min(lo, v.position);
            hi = glm::max(hi, v.position);
        }
    EXPECT_NEAR(hi.x - lo.x, 40.0f, 0.5f);
    EXPECT_NEAR(hi.z - lo.z, 10.0f, 0.5f);
    // the body extends away from the tissue
    EXPECT_LT(bounds(probe).min.y, -100.0f);
    EXPECT_LE(bounds(probe).max.y, 1e-4f);
}

TEST(Mesh, RecomputedNormalsOfAFlatGridPointUp)
{
    Mesh m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.vertices.push_back({{float(j), 0.0f, float(i)}, {}, {}});
    for (std::uint32_t k : {0u, 3u, 4u, 0u, 4u, 1u}) m.indices.push_back(k);
    recompute_normals(m);
    EXPECT_NEAR(std::abs(m.vertices[0].normal.y), 1.0f, 1e-6f);
}

TEST(Mesh, ABoxIsItsSixFacesInCellsNoLargerThanAsked)
{
    const glm::vec3 lo(-30, 0, -100), hi(30, 4, 160);  // 60 x 4 x 260 mm
    const Mesh box = make_box(lo, hi, glm::vec3(0.5f), 25.0f);
    ASSERT_EQ(box.indices.size() % 3, 0u);
    double area = 0;
    float longest = 0;
    for (std::size_t t = 0; t < box.indices.size(); t += 3) {
        const Vertex& a = box.vertices[box.indices[t]];
        const Vertex& b = box.vertices[box.indices[t + 1]];
        const Vertex& c = box.vertices[box.indices[t + 2]];
        const glm::vec3 cross = glm::cross(b.position - a.position, c.position - a.position);
        area += 0.5 * double(glm::length(cross));
        // counter-clockwise seen from outside: the winding agrees with the face's normal
        EXPECT_GT(glm::dot(cross, a.normal), 0.0f) << "triangle " << t / 3;
        for (const glm::vec3& e : {b.position - a.position, c.position - b.position})  // the quad's sides (not its diagonal)
            longest = std::max({longest, std::abs(e.x), std::abs(e.y), std::abs(e.z)});
    }
    // the box's surface, 2 (60*4 + 60*260 + 4*260) mm², covered once
    EXPECT_NEAR(area, 2.0 * (60 * 4 + 60 * 260 + 4 * 260), 1e-2);
    EXPECT_LE(longest, 25.0f + 1e-3f);
    // every vertex on the box's surface, on the face its normal names
    for (const Vertex& v : box.vertices) {
        const glm::vec3 n = v.normal;
        const float plane = glm::dot(n, n.x + n.y + n.z > 0 ? hi : lo);
        EXPECT_NEAR(glm::dot(n, v.position), plane, 1e-3f);
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(v.position, lo - 1e-3f)) && glm::all(glm::lessThanEqual(v.position, hi + 1e-3f)));
    }
    // (cells + 1)² vertices a face: 4 x 12 on the 60 x 260 faces, 2 x 12 on the 4 x 260, 4 x 2 on the 60 x 4
    EXPECT_EQ(box.vertices.size(), std::size_t(2 * 48 + 2 * 24 + 2 * 8));
}

}  // namespace
}  // namespace echosim::scene

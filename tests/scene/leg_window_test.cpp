// The exam patch as a window anywhere on the right leg (scene/leg.hpp): the same size as the home
// patch wherever it sits, and the static mesh's hole always closed by it exactly.
#include "scene/leg.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim::scene {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

using Key = std::tuple<float, float, float>;
Key key(glm::vec3 p) { return {p.x, p.y, p.z}; }

LegModel window_at(float z, float theta_deg)
{
    const LegModel home;
    LegOptions o;
    o.patch_centre = LimbCoordinates{home.limb_t_at_z(z), theta_deg * kDeg};
    return LegModel(o);
}

// The edges of the static mesh within 150 mm of `near` that only one of its triangles has (by
// position: the flat caps have vertices of their own where they meet the rest; the table's box,
// far away, has faces whose edges do not meet): the rim of the hole.
std::vector<std::pair<glm::vec3, glm::vec3>> open_edges(const Mesh& m, glm::vec3 near)
{
    std::map<std::pair<Key, Key>, int> count;
    std::map<std::pair<Key, Key>, std::pair<glm::vec3, glm::vec3>> ends;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            glm::vec3 a = m.vertices[m.indices[t + std::size_t(e)]].position, b = m.vertices[m.indices[t + std::size_t((e + 1) % 3)]].position;
            if (key(b) < key(a)) std::swap(a, b);
            const auto k = std::make_pair(key(a), key(b));
            ++count[k];
            ends[k] = {a, b};
        }
    std::vector<std::pair<glm::vec3, glm::vec3>> open;
    for (const auto& [k, n] : count)
        if (n == 1 && glm::length(ends[k].first - near) < 150.0f) open.push_back(ends[k]);
    return open;
}

// No crack: the hole's rim is made of exactly the window's cell edges (two per cell row and per
// cell column), each of whose ends is a patch border vertex bit for bit, and each patch border
// vertex lies on a rim edge (on a leg vertex, or on the straight edge between two).
void expect_closed(const LegModel& leg)
{
    const ExamPatch& p = leg.patch();
    const int r = leg.options().patch_refine;
    std::set<Key> border;
    std::vector<glm::vec3> border_points;
    for (int i = 0; i < p.rows; ++i)
        for (int j = 0; j < p.cols; ++j)
            if (i == 0 || j == 0 || i == p.rows - 1 || j == p.cols - 1) {
                const glm::vec3 v = p.rest.vertices[std::size_t(i * p.cols + j)].position;
                border.insert(key(v));
                border_points.push_back(v);
            }
    const auto rim = open_edges(leg.static_mesh(), leg.limb_point({p.centre_t(), p.centre_theta()}));
    const int cells_ring = p.cells.ring1 - p.cells.ring0, cells_seg = p.cells.seg1 - p.cells.seg0;
    EXPECT_EQ(int(rim.size()), 2 * (cells_ring + cells_seg)) << "the static mesh's only opening is the window's";
    for (const auto& [a, b] : rim) {
        EXPECT_TRUE(border.count(key(a))) << "rim vertex " << a.x << "," << a.y << "," << a.z << " is not a patch vertex";
        EXPECT_TRUE(border.count(key(b))) << "rim vertex " << b.x << "," << b.y << "," << b.z << " is not a patch vertex";
    }
    EXPECT_EQ(int(border_points.size()), 2 * (cells_ring + cells_seg) * r);
    for (const glm::vec3 v : border_points) {
        float nearest = 1e9f;
        for (const auto& [a, b] : rim) {
            const glm::vec3 ab = b - a;
            const float s = std::clamp(glm::dot(v - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
            nearest = std::min(nearest, glm::length(a + s * ab - v));
        }
        EXPECT_LT(nearest, 1e-4f) << "patch border vertex off the rim by " << nearest << " mm";
    }
}

TEST(LegWindow, TheHoleAndThePatchMeetWithoutACrackWhereverTheWindowSits)
{
    {
        SCOPED_TRACE("home");
        expect_closed(LegModel{});
    }
    struct Site {
        const char* name;
        float z, theta_deg;
    };
    for (const Site s : {Site{"inguinal ligament", 20, 305}, Site{"adductor canal", -300, 320}, Site{"popliteal fossa", -450, 45},
                         Site{"across theta 0 (medial)", -200, 2}, Site{"the ankle's end", -900, 180}}) {
        SCOPED_TRACE(s.name);
        expect_closed(window_at(s.z, s.theta_deg));
    }
}

TEST(LegWindow, TheHomePatchIsTheOneItAlwaysWas)
{
    const LegModel leg;
    const ExamPatch& p = leg.patch();
    // the rings nearest z = -30 and -150 mm, segments 278..332 degrees of 96
    EXPECT_EQ(p.cells, (PatchCells{37, 52, 74, 89}));
    EXPECT_EQ(p.rows, 61);
    EXPECT_EQ(p.cols, 61);
    EXPECT_FALSE(leg.options().patch_centre.has_value());
}

// Wherever it sits, a window covers as much skin as the home patch does, within a cell.
TEST(LegWindow, AWindowIsTheHomePatchsSizeAnywhere)
{
    const LegModel home;
    EXPECT_NEAR(home.window_along_mm(), 120.0f, 10.0f);
    EXPECT_NEAR(home.window_around_mm(), 80.0f, 10.0f);
    for (const auto& [z, theta] : {std::pair{-300.0f, 320.0f}, {-450.0f, 45.0f}, {-200.0f, 2.0f}}) {
        const LegModel w = window_at(z, theta);
        const ExamPatch& p = w.patch();
        const float mid_theta = p.centre_theta(), mid_t = p.centre_t();
        // along, through the middle: the sum of the rings' chords
        float along = 0;
        for (int i = p.cells.ring0; i < p.cells.ring1; ++i) {
            const float rps = float(w.options().rings_per_span);
            along += glm::length(w.limb_point({float(i + 1) / rps, mid_theta}) - w.limb_point({float(i) / rps, mid_theta}));
        }
        const float ring_mm = along / float(p.cells.ring1 - p.cells.ring0);
        // each end within half a ring of where it would be, measured on a line within half a segment
        EXPECT_NEAR(along, home.window_along_mm(), 1.5f * ring_mm) << "z " << z;
        float around = 0;
        const int n = p.cells.seg1 - p.cells.seg0;
        for (int j = 0; j < n; ++j)
            around += glm::length(w.limb_point({mid_t, p.theta0 + (p.theta1 - p.theta0) * float(j + 1) / float(n)}) -
                                  w.limb_point({mid_t, p.theta0 + (p.theta1 - p.theta0) * float(j) / float(n)}));
        EXPECT_NEAR(around, home.window_around_mm(), around / float(n)) << "z " << z;
        // centred where asked, within half a cell each way
        const glm::vec3 asked = w.limb_point({home.limb_t_at_z(z), theta * kDeg}), centre = w.limb_point({mid_t, mid_theta});
        EXPECT_LT(std::abs(centre.z - asked.z), 0.5f * ring_mm + 0.5f) << "z " << z;
        EXPECT_LT(glm::length(centre - asked), 0.5f * std::hypot(ring_mm, around / float(n)) + 0.5f) << "z " << z;
    }
}

TEST(LegWindow, LimbCoordinatesFindTheSkinPointBack)
{
    const LegModel leg;
    for (float t : {1.3f, 2.0f, 2.6f, 4.1f, 6.5f, 7.9f})
        for (float theta : {0.1f, 1.5f, 3.0f, 4.7f, 6.2f}) {
            const glm::vec3 p = leg.limb_point({t, theta});
            const LimbCoordinates c = leg.limb_coordinates(p);
            EXPECT_NEAR(c.t, t, 1e-4f);
            EXPECT_NEAR(c.theta, theta, 1e-4f);
            // 20 mm out from the ring's centre, in the ring's plane: the same coordinates
            const glm::vec3 centre = leg.exam_limb().at(t).center;
            const LimbCoordinates out = leg.limb_coordinates(p + 20.0f * glm::normalize(p - centre));
            EXPECT_NEAR(out.t, t, 1e-4f);
            EXPECT_NEAR(out.theta, theta, 1e-4f);
        }
    EXPECT_EQ(leg.limb_t_at_z(1000.0f), 0.0f);
    EXPECT_EQ(leg.limb_t_at_z(-5000.0f), leg.exam_limb().t_max());
}

TEST(LegWindow, ACentreThatIsNotFiniteIsRefused)
{
    LegOptions o;
    o.patch_centre = LimbCoordinates{std::nanf(""), 0.0f};
    EXPECT_THROW(LegModel{o}, std::invalid_argument);
}

}  // namespace
}  // namespace echosim::scene

// The probe's indentation profile (session/indentation.hpp) against its definition, the
// Gaussian-weighted mean over every tissue node under the face, computed here in double without
// the profile's lateral cut-off; and against what a uniform push must give whatever the weights.
#include "session/indentation.hpp"

#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <gtest/gtest.h>

#include "core/probe_spec.hpp"
#include "physics/compiled_model.hpp"
#include "physics/physics_fixture.hpp"

namespace echosim::session {
namespace {

std::vector<echo::ColumnProfile> by_definition(const std::vector<glm::dvec3>& rest, const std::vector<float>& positions, const Pose& face,
                                               const echo::ImagePlane& plane, double spacing, double press_mm)
{
    const glm::dquat to_probe = glm::conjugate(glm::dquat(face.orientation));
    const glm::dvec3 origin(face.position);
    const double half_width = 0.5 * plane.width_mm + 2 * spacing, half_thickness = 0.5 * kLinearProbe.face_thickness_mm + 2 * spacing;
    const double sx = 0.6 * spacing, sz = std::max(0.5 * kLinearProbe.face_thickness_mm, spacing);
    std::vector<echo::ColumnProfile> out(plane.columns);
    for (std::uint32_t c = 0; c < plane.columns; ++c) {
        const double x = (c + 0.5) * plane.pixel_x_mm() - 0.5 * plane.width_mm;
        double w_sum = 0, y_sum = 0, shift_sum = 0;
        for (std::size_t i = 0; i < rest.size(); ++i) {
            const glm::dvec3 r = to_probe * (rest[i] - origin);
            if (std::abs(r.x) > half_width || std::abs(r.z) > half_thickness) continue;
            const glm::dvec3 p = to_probe * (glm::dvec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]) - origin);
            const double w = std::exp(-0.5 * (std::pow((r.x - x) / sx, 2) + std::pow(r.z / sz, 2)));
            w_sum += w, y_sum += w * r.y, shift_sum += w * (p.y - r.y);
        }
        out[c] = w_sum > 1e-6 ? echo::ColumnProfile{float(y_sum / w_sum), float(shift_sum / w_sum)} : echo::ColumnProfile{float(-press_mm), 0};
    }
    return out;
}

TEST(IndentationProfile, IsTheWeightedMeanOfTheNodesUnderTheFace)
{
    const auto model = physics::compile_model(test::shipped_model(2), physics::PhysicsOptions{});
    const IndentationProfile profile(*model);
    const Pose face = test::leg().probe_rest_pose(0.5f, 0.5f);
    const glm::dvec3 beam(face.axis_y()), lateral(face.axis_x());
    std::vector<glm::dvec3> rest(model->node_count());
    for (std::size_t i = 0; i < rest.size(); ++i) rest[i] = {model->rest[3 * i], model->rest[3 * i + 1], model->rest[3 * i + 2]};
    const echo::ImagePlane plane;  // the live image's 400 columns across 40 mm

    // pushed along the beam by 3 + 2 sin(x / 7) mm, x the node's lateral place under the face
    std::vector<float> positions(3 * rest.size()), uniform(3 * rest.size());
    for (std::size_t i = 0; i < rest.size(); ++i) {
        const double x = glm::dot(rest[i] - glm::dvec3(face.position), lateral);
        const glm::dvec3 p = rest[i] + (3.0 + 2.0 * std::sin(x / 7.0)) * beam, q = rest[i] + 4.0 * beam;
        for (int k = 0; k < 3; ++k) positions[3 * i + std::size_t(k)] = float(p[k]), uniform[3 * i + std::size_t(k)] = float(q[k]);
    }
    std::vector<echo::ColumnProfile> got;
    profile.compute(face, 0.0, positions, plane, got);
    const std::vector<echo::ColumnProfile> want = by_definition(rest, positions, face, plane, profile.node_spacing_mm(), 0.0);
    ASSERT_EQ(got.size(), plane.columns);
    double lowest = 1e9, highest = -1e9;
    for (std::uint32_t c = 0; c < plane.columns; ++c) {
        EXPECT_NEAR(got[c].skin_y_mm, want[c].skin_y_mm, 1e-4) << "column " << c;
        EXPECT_NEAR(got[c].skin_shift_mm, want[c].skin_shift_mm, 1e-4) << "column " << c;
        lowest = std::min(lowest, double(got[c].skin_shift_mm));
        highest = std::max(highest, double(got[c].skin_shift_mm));
    }
    EXPECT_GT(highest - lowest, 2.0) << "the profile follows the push along the array, not one scalar";

    // a uniform push is the same at every column, whatever the weights
    profile.compute(face, 0.0, uniform, plane, got);
    for (std::uint32_t c = 0; c < plane.columns; ++c) ASSERT_NEAR(got[c].skin_shift_mm, 4.0, 1e-4) << "column " << c;
}

}  // namespace
}  // namespace echosim::session

#include "session/session.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <gtest/gtest.h>

#include "tissue/physical_ranges.hpp"

namespace echosim::session {
namespace {

// The patch vertex nearest the probe's resting point: how far it has been pushed in [mm].
double patch_push(Session& s, const Pose& rest)
{
    const auto& verts = *s.view().patch;
    const auto& rest_verts = s.leg().patch().rest.vertices;
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < rest_verts.size(); ++k)
        if (glm::length(rest_verts[k].position - rest.position) < glm::length(rest_verts[nearest].position - rest.position)) nearest = k;
    return glm::dot(verts[nearest].position - rest_verts[nearest].position, rest.axis_y());
}

TEST(Session, StartsAtRestWithTheProbeOnThePatchCentre)
{
    Session s;
    const SessionView& v = s.view();
    EXPECT_EQ(v.probe_force_N, 0.0);
    EXPECT_EQ(v.time_s, 0.0);
    const Pose centre = s.leg().probe_rest_pose(0.5f, 0.5f);
    EXPECT_EQ(v.probe.position, centre.position);
    ASSERT_EQ(v.patch->size(), s.leg().patch().rest.vertices.size());
    for (std::size_t k = 0; k < v.patch->size(); ++k) EXPECT_EQ((*v.patch)[k].position, s.leg().patch().rest.vertices[k].position);
}

// Lock-step: the clock is simulated time; each advance runs exactly the physics steps it covers.
TEST(Session, LockStepAdvancesThePhysicsBySimulatedTime)
{
    Session s;
    const double h = SessionOptions{}.physics.time_step;
    for (int i = 0; i < 25; ++i) s.advance(h);
    EXPECT_EQ(s.physics_stats().steps, 25);
    s.advance(10 * h);
    EXPECT_EQ(s.physics_stats().steps, 35);
    EXPECT_NEAR(s.view().time_s, 35 * h, 1e-12);
    EXPECT_NEAR(s.time(), 35 * h, 1e-12);
}

TEST(Session, TheCommandedProbeIsPressedAlongItsBeam)
{
    Session s;
    const Pose rest = s.leg().probe_rest_pose(0.4f, 0.6f);
    s.place_probe({rest, 7.5});
    const Pose face = s.view().probe;
    EXPECT_LT(glm::length(face.position - (rest.position + 7.5f * rest.axis_y())), 1e-4f);
    EXPECT_EQ(face.orientation, rest.orientation);
}

// The same indentation drives what is felt and what is seen: pressing deeper gives a larger force
// and a deeper dent in the drawn patch, read from the same view.
TEST(Session, ADeeperPressPushesBackHarderAndDentsTheSkinFurther)
{
    const Pose rest = Session().leg().probe_rest_pose(0.5f, 0.5f);
    double force[2], dent[2];
    const double press[2] = {4.0, 10.0};
    for (int k = 0; k < 2; ++k) {
        Session s;
        s.press_and_settle(rest, press[k]);
        force[k] = s.view().probe_force_N;
        dent[k] = patch_push(s, rest);
        EXPECT_EQ(s.view().resets, 0);
        // the skin under the face follows it to within the contact's sinking (a few tenths of a mm)
        EXPECT_NEAR(dent[k], press[k], 1.0) << press[k] << " mm";
    }
    EXPECT_GT(force[0], 0.1);
    EXPECT_GT(force[1], force[0] * 1.5);
    EXPECT_GT(dent[1], dent[0] + 4.0);
}

TEST(Session, SameScriptSameResult)
{
    auto run = [] {
        Session s;
        for (int i = 0; i < 200; ++i) {
            s.place_probe_on_patch(0.5f, 0.45f + 0.0005f * float(i), 6.0 * std::min(1.0, i / 50.0));
            s.advance(1e-3);
        }
        return std::pair(s.view().probe_force_N, *s.view().patch);
    };
    const auto a = run(), b = run();
    EXPECT_GT(a.first, 0.1);
    EXPECT_EQ(a.first, b.first);
    for (std::size_t k = 0; k < a.second.size(); ++k) ASSERT_EQ(a.second[k].position, b.second[k].position) << k;
}

TEST(Session, RefusesWhatIsNotAProbeOrATime)
{
    Session s;
    EXPECT_THROW(s.place_probe({s.leg().probe_rest_pose(0.5f, 0.5f), -1.0}), std::invalid_argument);
    EXPECT_THROW(s.place_probe({s.leg().probe_rest_pose(0.5f, 0.5f), std::nan("")}), std::invalid_argument);
    Pose not_a_rotation = s.leg().probe_rest_pose(0.5f, 0.5f);
    not_a_rotation.orientation = glm::quat(2.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_THROW(s.place_probe({not_a_rotation, 1.0}), std::invalid_argument);
    Pose far_away = s.leg().probe_rest_pose(0.5f, 0.5f);
    far_away.position.x = std::numeric_limits<float>::infinity();
    EXPECT_THROW(s.place_probe({far_away, 1.0}), std::invalid_argument);
    EXPECT_EQ(s.probe().rest.position, s.leg().probe_rest_pose(0.5f, 0.5f).position) << "a refused placement moves nothing";
    EXPECT_THROW(s.advance(0.0), std::invalid_argument);
    EXPECT_THROW(s.advance(-1e-3), std::invalid_argument);
    Session real_time({.clock = Clock::real_time});
    EXPECT_THROW(real_time.press_and_settle(real_time.probe().rest, 3.0), std::logic_error);
    real_time.stop();
}

// Issue 34: every model inside the physical ranges pushes back harder the deeper it is pressed, to
// the deepest press allowed. The corners of the ranges that make the contact's job hardest (the
// stiffest rest stiffness, the shallowest bottoming depth), and the shipped thigh, settled at
// 20, 22.5 and 25 mm. (The ranges before held models whose force fell: 105 N at 15 mm, 41 N at 25.)
TEST(Session, EveryModelInTheRangesPushesBackHarderTheDeeperItIsPressed)
{
    tissue::SampleParameters corner;
    for (std::size_t i = 0; i < corner.b.size(); ++i) {
        corner.b[i] = 1.0 / tissue::kRestStiffness.hi;
        corner.a[i] = corner.b[i] / tissue::kBottomingDepth.lo;
    }
    corner.lambda = 5.8e-4;  // the shipped thigh's membrane and damping
    corner.mu = 9.1e-4;
    ASSERT_FALSE(tissue::sample_parameters_defect(corner)) << tissue::sample_parameters_defect(corner).why;
    for (const std::optional<tissue::SampleParameters>& model : {std::optional<tissue::SampleParameters>(corner), std::optional<tissue::SampleParameters>()}) {
        SessionOptions options;
        options.tissue = model;
        Session s(options);
        double before = 0;
        for (double press : {20.0, 22.5, Session::kMaxPressMm}) {
            const SettleReport r = s.press_and_settle(s.probe().rest, press);
            ASSERT_TRUE(r.settled) << not_settled_message(press, r);
            EXPECT_GT(r.force_N, before) << (model ? "corner" : "thigh") << " at " << press << " mm";
            before = r.force_N;
        }
    }
}

// A press is held until the force on the probe stops changing; the force it then reports is the
// one a much longer hold reaches.
TEST(Session, APressSettlesBeforeItsForceIsReported)
{
    Session s;
    const SettleReport r = s.press_and_settle(s.probe().rest, 8.0);
    ASSERT_TRUE(r.settled) << not_settled_message(8.0, r);
    EXPECT_GE(r.seconds, 0.4 - 1e-9);
    EXPECT_LT(r.drift_N, settled_change_N(r.force_N));
    EXPECT_EQ(r.resets, 0);
    EXPECT_NEAR(r.force_N, s.view().probe_force_N, r.ripple_N + 1e-9);
    Session longer;
    longer.press_and_settle(longer.probe().rest, 8.0, 2.5);
    EXPECT_NEAR(r.force_N, longer.view().probe_force_N, 0.02 * r.force_N);
}

// Pressed deep, the skin wraps the ends of the probe's array; it settles there, and the force is
// steady from step to step. (With sharp ends whose pressure faded over 1 mm it chattered: +-16 % at
// 16 mm, +-28 % at 20 mm, and the tissue never slept under the probe.)
TEST(Session, ADeepPressHoldsASteadyForce)
{
    for (double press : {16.0, 20.0}) {
        Session s;
        const SettleReport r = s.press_and_settle(s.probe().rest, press);
        ASSERT_TRUE(r.settled) << not_settled_message(press, r);
        EXPECT_GT(r.force_N, 5.0) << press << " mm";
        EXPECT_LT(r.ripple_N, 0.002 * r.force_N) << press << " mm: " << r.force_N << " N";
        // (the skin in the long sides' fade moves across them only as fast as the step can follow,
        // contact::add_contact_stiffness_product: at rest after 0.5 and 0.7 s here, was 0.2 s)
        s.advance(1.0);
        EXPECT_GT(s.physics_stats().asleep, 0) << press << " mm: the tissue should come to rest under a still probe";
    }
}

// A model that creeps (a damping of 65,537 N s/mm, which the model file's reader refuses, given
// here directly) does not settle in kMaxSettleS: the report says so instead of a force.
TEST(Session, ATissueThatCreepsIsReportedUnsettled)
{
    SessionOptions options;
    options.refine = 2;
    tissue::SampleParameters p;
    for (std::size_t i = 0; i < p.a.size(); ++i) p.b[i] = 5.0, p.a[i] = 0.1;
    p.lambda = 5e-4;
    p.mu = 65537.0;
    options.tissue = p;
    Session s(options);
    const SettleReport r = s.press_and_settle(s.probe().rest, 1.0);
    EXPECT_FALSE(r.settled);
    EXPECT_NEAR(r.seconds, kMaxSettleS, 1e-6);
    EXPECT_GE(r.drift_N, settled_change_N(r.force_N));
    const std::string why = not_settled_message(1.0, r);
    EXPECT_NE(why.find("has not settled under a 1.00 mm press after 3.0 s"), std::string::npos) << why;
    // pressed to a force, it fails too: here at the deepest press, which passes through a skin that
    // cannot follow it (no skin left under the face to push back)
    Session again(options);
    EXPECT_THROW(again.press_to_force(again.probe().rest, 0.2), std::invalid_argument);
}

}  // namespace
}  // namespace echosim::session

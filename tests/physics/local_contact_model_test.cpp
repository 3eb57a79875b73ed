// The local contact model the haptic thread will render (physics/local_contact_model) against the
// full dynamics: pressed and settled, the probe advances a little further; the model's predicted
// force must match where the tissue settles to within 30 % of the change. Measured: 2, 7, 22 and
// 25 % at 4, 8, 12 and 16 mm, always over. The model holds the skin where it is and takes each
// node's penalty in series with its tissue column; pressed deeper, the skin draped over the face's
// long edges slides off their fade, which it cannot know. A quarter of the 0.2 N a 0.3 mm push adds
// is 0.05 N, and the physics refreshes the model every step. (With the sharp ends of before, 1-2 %
// at 4 and 8 mm; deeper presses rippled too much to test.)
#include "physics/local_contact_model.hpp"

#include <gtest/gtest.h>

#include "physics/physics_fixture.hpp"
#include "physics/simulation.hpp"

namespace echosim::physics {
namespace {

struct Pressed {
    Simulation sim{compile_model(test::shipped_model(7), PhysicsOptions{})};
    TissueState& state = sim.state;
    Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);

    Eigen::Vector3d face(double press) const { return contact::probe_at(pressed_along_beam(rest, press)).position; }
    // holds the probe `press` mm in for `steps` steps
    void hold(double press, int steps)
    {
        state.probe = contact::probe_at(pressed_along_beam(rest, press));
        for (int i = 0; i < steps; ++i) sim.step();
    }
};

TEST(LocalContactModel, PredictsTheSettledForceOfASmallFurtherPush)
{
    for (double depth : {4.0, 8.0, 12.0, 16.0}) {
        Pressed p;
        for (int i = 1; i <= 100; ++i) p.hold(depth * i / 100.0, 1);  // in over 0.1 s
        p.hold(depth, 400);
        const LocalContactModel model = local_contact_model(*p.sim.model, p.state);
        ASSERT_TRUE(model.in_contact);
        EXPECT_NEAR(model.force, p.state.last.probe_force_N, 1e-12);
        EXPECT_GT(model.stiffness, 0.0);
        EXPECT_GT(model.damping, 0.0);

        const double push = 0.3;  // [mm]
        p.hold(depth + push, 400);
        const double settled = p.state.last.probe_force_N, change = settled - model.force;
        const double predicted = model.force_at(p.face(depth + push), Eigen::Vector3d::Zero());
        EXPECT_GT(change, 0.02 * model.force) << "the push should be felt at " << depth << " mm";
        EXPECT_LT(std::abs(predicted - settled), 0.3 * change) << "at " << depth << " mm: " << model.force << " N -> " << settled
                                                                << " N, predicted " << predicted << " N";
    }
}

TEST(LocalContactModel, NoContactNoForce)
{
    Pressed p;
    p.hold(-5.0, 2);  // 5 mm above the skin
    const LocalContactModel model = local_contact_model(*p.sim.model, p.state);
    EXPECT_FALSE(model.in_contact);
    EXPECT_EQ(model.force_at(p.face(10.0), Eigen::Vector3d::Zero()), 0.0);
}

TEST(LocalContactModel, NeverPulls)
{
    LocalContactModel m;
    m.in_contact = true;
    m.force = 2.0;
    m.stiffness = 1.0;
    EXPECT_DOUBLE_EQ(m.force_at(m.face + 1.0 * m.axis, Eigen::Vector3d::Zero()), 3.0);
    EXPECT_DOUBLE_EQ(m.force_at(m.face - 5.0 * m.axis, Eigen::Vector3d::Zero()), 0.0);  // withdrawn past the skin
}

}  // namespace
}  // namespace echosim::physics

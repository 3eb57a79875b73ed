// The whole force path with the simulated arm standing in for a real one, lock-step: the haptic loop
// renders the tissue's push from the physics' local model and sends it to the arm, the arm's handle
// moves under it and under the hand holding it, and its pose comes back as the probe's. A hand held
// 15 mm below the skin does not get there: the handle settles where the coupling's pull equals the
// force the loop sends, and that force is what the physics says the thigh pushes back with.
#include <chrono>
#include <algorithm>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "device/simulated_arm.hpp"
#include "haptics/haptic_loop.hpp"
#include "physics/physics_fixture.hpp"

namespace echosim::device {
namespace {

TEST(ArmForcePath, TheHandleSettlesWhereTheHandsPullMeetsTheTissuesPush)
{
    physics::PhysicsOptions po;
    po.steps_per_publish = 10;
    physics::PhysicsRunner physics(test::shipped_model(3), po);
    const haptics::ProbeMapping mapping(test::leg());  // the workspace origin 20 mm above the skin

    SimulatedArmOptions o;
    o.servo = SimulatedArmOptions::Servo::lock_step;
    o.hand.kind = HandScript::Kind::hold;
    o.hand.hold_mm = Eigen::Vector3d(0, -35, 0);  // 15 mm into the skin, were nothing pushing back
    o.arm.coulomb_N = 0;                           // no friction band: the balance is exact
    auto arm = std::make_shared<SimulatedArm>(o);
    haptics::HapticLoop loop(physics, arm, mapping);

    double last_y = 0;
    for (int i = 1; i <= 3000; ++i) {
        const double t = i * 1e-3;
        loop.tick(t);
        physics.step_to(t);
        last_y = loop.latest().device.position.y();
    }
    const haptics::HapticSample& s = loop.latest();
    const Eigen::Vector3d felt = mapping.to_device(s.force.world_N, Control::workspace);  // what the arm was sent
    ASSERT_GT(felt.y(), 0.5) << "the thigh pushes the handle up";
    // pressed in, but less than the hand's 15 mm: the tissue held the handle back
    const double press_mm = -20.0 - last_y;
    EXPECT_GT(press_mm, 1.0);
    EXPECT_LT(press_mm, 15.0);
    // at rest the coupling's pull balances the force sent: k (y - y_hand) = F_y
    EXPECT_NEAR(o.arm.coupling_N_per_mm * (last_y - o.hand.hold_mm.y()), felt.y(), 0.02);
    EXPECT_LT((arm->applied_force() - felt).norm(), 1e-9);
    // and that force is the physics' own, within the arm's limit
    EXPECT_LE(s.force.along_N, arm->capabilities().max_force_N + 1e-12);
    if (s.force.along_N < arm->capabilities().max_force_N) {
        EXPECT_NEAR(s.force.along_N, s.physics_force_N, 0.05 * s.physics_force_N + 0.02);
    }
}

// A whole press cycle of the demo's hand (down 25 mm into the skin and back over 4 s): the force the
// arm feels rises and falls smoothly, with no chatter of the handle against the tissue (the
// stiffness and damping it renders are within what its mass and friction keep stable at 1 kHz).
TEST(ArmForcePath, OverTheDemosPressCycleTheForceIsSmooth)
{
    physics::PhysicsOptions po;
    po.steps_per_publish = 10;
    physics::PhysicsRunner physics(test::shipped_model(3), po);
    const haptics::ProbeMapping mapping(test::leg());
    SimulatedArmOptions o;
    o.servo = SimulatedArmOptions::Servo::lock_step;
    auto arm = std::make_shared<SimulatedArm>(o);
    haptics::HapticLoop loop(physics, arm, mapping);
    double last = 0, max_jump = 0, peak = 0, deepest = 0;
    int sign_changes = 0;
    double last_step = 0;
    for (int i = 1; i <= 4000; ++i) {
        const double t = i * 1e-3;
        loop.tick(t);
        physics.step_to(t);
        const haptics::HapticSample& s = loop.latest();
        const double f = s.force.along_N, step = f - last;
        max_jump = std::max(max_jump, std::abs(step));
        if (step * last_step < 0 && std::abs(step) > 1e-3) ++sign_changes;
        if (std::abs(step) > 1e-3) last_step = step;
        last = f;
        peak = std::max(peak, f);
        deepest = std::min(deepest, s.device.position.y());
    }
    // measured: 5.4 N at the deepest, the handle 7 mm into the skin (the hand 25 mm), 0.013 N a tick at most
    EXPECT_GT(peak, 2.0);
    EXPECT_LT(deepest, -20.0) << "the handle never reached the skin";
    EXPECT_GT(deepest, -45.0 + 5.0) << "the hand went through the thigh as if it were not there";
    EXPECT_LT(max_jump, 0.05) << "a step in the force, 1 ms apart";
    EXPECT_LE(sign_changes, 2) << "the force rose and fell more than once: the handle chattered against the skin";
}

// The same path in real time, each part on its own thread (the physics, the haptic loop, the arm's
// servo), then stopped: the loop's last command is a zero force, and the arm applies it from its
// next servo tick (the order Ctrl-C or SIGTERM stops a run in).
TEST(ArmForcePath, InRealTimeTheArmFeelsTheThighAndALoopThatStopsLeavesItNoForce)
{
    using namespace std::chrono;
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const haptics::ProbeMapping mapping(test::leg());
    SimulatedArmOptions o;
    o.hand.kind = HandScript::Kind::hold;
    o.hand.hold_mm = Eigen::Vector3d(0, -35, 0);
    auto arm = std::make_shared<SimulatedArm>(o);
    haptics::HapticOptions ho;
    ho.realtime_priority = false;  // a test asks for no privileges
    haptics::HapticLoop loop(physics, arm, mapping, ho);
    physics.start();
    loop.start();
    // the handle starts where the hand holds it, 15 mm into the skin: the loop soon pushes it back
    const auto give_up = steady_clock::now() + seconds(5);
    while (arm->applied_force().y() < 0.5 && steady_clock::now() < give_up) std::this_thread::sleep_for(milliseconds(5));
    EXPECT_GE(arm->applied_force().y(), 0.5) << "the thigh never pushed the handle back";
    loop.stop();
    const std::int64_t stopped_at = arm->servo_ticks();
    while (arm->servo_ticks() < stopped_at + 2 && steady_clock::now() < give_up + seconds(1)) std::this_thread::sleep_for(microseconds(200));
    EXPECT_EQ(arm->applied_force(), Eigen::Vector3d::Zero());
    physics.stop();
}

}  // namespace
}  // namespace echosim::device

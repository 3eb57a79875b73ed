// The simulated arm (device/simulated_arm.cpp, device/arm_dynamics.cpp) against the closed forms of
// its mechanics: a mass against viscous friction under a constant force, dry friction's threshold,
// the coupling's spring settling at F/k, the end stops; then the device's own servo, lock-step and
// threaded, its force cut, and a zero force honoured at the next tick.
#include "device/simulated_arm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace echosim::device {
namespace {

// a handle let go (no hand), against viscous friction only
ArmParameters free_handle()
{
    ArmParameters p;
    p.mass_kg = 0.1;
    p.viscous_N_s_per_mm = 0.002;
    p.coulomb_N = 0;
    p.coupling_N_per_mm = 0;
    p.coupling_N_s_per_mm = 0;
    p.workspace_mm = Eigen::Vector3d(400, 400, 400);
    return p;
}

TEST(ArmDynamics, AConstantForceAgainstViscousFrictionGivesTheFirstOrderResponse)
{
    const ArmParameters p = free_handle();
    const double f = 0.1;                                   // [N]
    const double v_end = f / p.viscous_N_s_per_mm;          // 50 mm/s
    const double tau = p.mass_kg / (1000.0 * p.viscous_N_s_per_mm);  // 0.05 s
    ArmState s;
    const double dt = 1e-3;
    for (int i = 1; i <= 1000; ++i) {
        step(p, s, Eigen::Vector3d::Zero(), Eigen::Vector3d(f, 0, 0), dt);
        const double t = i * dt;
        // v(t) = F/c (1 - e^(-t/tau)); the implicit damper lags the exponential by at most dt/tau of it
        EXPECT_NEAR(s.velocity_mm_s.x(), v_end * (1.0 - std::exp(-t / tau)), 0.02 * v_end) << "at " << t << " s";
    }
    EXPECT_NEAR(s.velocity_mm_s.x(), v_end, 1e-6 * v_end);
    // x(t) = F/c (t - tau (1 - e^(-t/tau))): 47.5 mm after 1 s
    EXPECT_NEAR(s.position_mm.x(), v_end * (1.0 - tau * (1.0 - std::exp(-1.0 / tau))), 0.01);
    EXPECT_EQ(s.position_mm.y(), 0.0);
    EXPECT_EQ(s.position_mm.z(), 0.0);
}

TEST(ArmDynamics, DryFrictionHoldsAForceBelowItAndTakesItsShareAboveIt)
{
    ArmParameters p = free_handle();
    p.coulomb_N = 0.03;
    ArmState held;
    for (int i = 0; i < 1000; ++i) step(p, held, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0.02, 0), 1e-3);
    EXPECT_EQ(held.position_mm, Eigen::Vector3d::Zero());  // 0.02 N < 0.03 N: it never starts

    ArmState sliding;
    const Eigen::Vector3d f(0.0, 0.08, 0.06);  // 0.1 N, not along an axis
    for (int i = 0; i < 1000; ++i) step(p, sliding, Eigen::Vector3d::Zero(), f, 1e-3);
    // (|F| - Fc) / c along F: 35 mm/s
    EXPECT_LT((sliding.velocity_mm_s - (0.1 - 0.03) / p.viscous_N_s_per_mm * f.normalized()).norm(), 1e-4);

    // let go: friction stops it, and never sends it back
    for (int i = 0; i < 2000; ++i) {
        step(p, sliding, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1e-3);
        EXPECT_GE(sliding.velocity_mm_s.dot(f), 0.0);
    }
    EXPECT_EQ(sliding.velocity_mm_s, Eigen::Vector3d::Zero());
}

TEST(ArmDynamics, TheCouplingSpringSettlesAtTheForceOverItsStiffness)
{
    ArmParameters p;  // the defaults, dry friction off so the rest is exact
    p.coulomb_N = 0;
    const Eigen::Vector3d hand(5, -30, 2);
    ArmState s{hand, Eigen::Vector3d::Zero()};
    const Eigen::Vector3d f(0, 1.5, -0.3);  // the tissue pushing the handle up, and a little towards the arm
    for (int i = 0; i < 3000; ++i) step(p, s, hand, f, 1e-3);
    EXPECT_LT((s.position_mm - (hand + f / p.coupling_N_per_mm)).norm(), 1e-6);  // 5 mm up, 1 mm back
    EXPECT_LT(s.velocity_mm_s.norm(), 1e-6);
}

TEST(ArmDynamics, TheHandleStopsAtTheWorkspacesFaces)
{
    ArmParameters p = free_handle();
    p.workspace_mm = Eigen::Vector3d(160, 120, 70);
    ArmState s;
    for (int i = 0; i < 3000; ++i) step(p, s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, -1, 0), 1e-3);
    EXPECT_DOUBLE_EQ(s.position_mm.y(), -60.0);
    EXPECT_EQ(s.velocity_mm_s.y(), 0.0);
    EXPECT_STREQ(invalid_field(p), "");
    p.mass_kg = 0;
    EXPECT_STREQ(invalid_field(p), "mass_kg");
}

SimulatedArmOptions holding(const Eigen::Vector3d& hand, SimulatedArmOptions::Servo servo)
{
    SimulatedArmOptions o;
    o.servo = servo;
    o.hand.kind = HandScript::Kind::hold;
    o.hand.hold_mm = hand;
    o.arm.coulomb_N = 0;
    return o;
}

TEST(SimulatedArm, LockStepStepsTheSameMechanicsAndCutsTheForce)
{
    const Eigen::Vector3d hand(0, -30, 0);
    SimulatedArm arm(holding(hand, SimulatedArmOptions::Servo::lock_step));
    EXPECT_EQ(arm.capabilities().control, Control::workspace);
    EXPECT_DOUBLE_EQ(arm.capabilities().max_force_N, 6.0);
    ArmParameters p = holding(hand, SimulatedArmOptions::Servo::lock_step).arm;
    ArmState twin{hand, Eigen::Vector3d::Zero()};

    DeviceSample s;
    ASSERT_TRUE(arm.read(0.0, s));
    EXPECT_EQ(s.position, hand);
    for (int i = 1; i <= 2000; ++i) {
        arm.write_force(Eigen::Vector3d(0, 20, 0));  // 20 N asked: 6 N sent
        ASSERT_TRUE(arm.read(i * 1e-3, s));
        step(p, twin, hand, Eigen::Vector3d(0, 6, 0), 1e-3);
        ASSERT_LT((s.position - twin.position_mm).norm(), 1e-9) << "tick " << i;
    }
    EXPECT_LT((s.position - (hand + Eigen::Vector3d(0, 6.0 / p.coupling_N_per_mm, 0))).norm(), 1e-3);
    EXPECT_LT((arm.applied_force() - Eigen::Vector3d(0, 6, 0)).norm(), 1e-12);
    arm.write_force(Eigen::Vector3d(std::nan(""), 1, 0));
    arm.read(2.001, s);
    EXPECT_EQ(arm.applied_force(), Eigen::Vector3d::Zero());
}

TEST(SimulatedArm, ItsServoThreadSettlesTheCouplingAndHonoursAZeroForceAtItsNextTick)
{
    using namespace std::chrono;
    const Eigen::Vector3d hand(0, -30, 0);
    const Eigen::Vector3d f(0, 1.5, 0);
    {
        SimulatedArm arm(holding(hand, SimulatedArmOptions::Servo::thread));
        std::vector<DeviceEvent> events;
        arm.events(events);
        ASSERT_EQ(events.size(), 1u);
        EXPECT_EQ(events[0].kind, DeviceEvent::Kind::connected);
        // a loop sending the force every millisecond for 0.6 s (the coupling settles in about 0.2 s);
        // the handle's height read over the last 0.3 s, its median taken: a test thread held up past
        // kForceHoldS on a loaded machine lets the handle sag for a moment, as it should
        const auto start = steady_clock::now();
        std::vector<double> heights;
        DeviceSample s;
        while (steady_clock::now() < start + milliseconds(600)) {
            arm.write_force(f);
            std::this_thread::sleep_for(milliseconds(1));
            if (steady_clock::now() > start + milliseconds(300) && arm.read(0.0, s)) heights.push_back(s.position.y());
        }
        ASSERT_GT(heights.size(), 20u);
        std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
        EXPECT_NEAR(heights[heights.size() / 2], hand.y() + 1.5 / 0.3, 0.05);  // F/k = 5 mm above the hand
        EXPECT_GT(arm.servo_ticks(), 300);  // about 600 at 1 kHz, fewer on a loaded machine

        // the stop's zero: applied from the servo's next tick
        arm.write_force(Eigen::Vector3d::Zero());
        const std::int64_t sent_at = arm.servo_ticks();
        while (arm.servo_ticks() < sent_at + 2) std::this_thread::sleep_for(microseconds(200));
        EXPECT_EQ(arm.applied_force(), Eigen::Vector3d::Zero());

        // a force not renewed is dropped after kForceHoldS
        arm.write_force(f);
        const std::int64_t renewed_at = arm.servo_ticks();
        while (arm.servo_ticks() < renewed_at + 2) std::this_thread::sleep_for(microseconds(200));
        EXPECT_EQ(arm.applied_force(), f);
        std::this_thread::sleep_for(duration<double>(kForceHoldS * 2));
        EXPECT_EQ(arm.applied_force(), Eigen::Vector3d::Zero());
    }
}

TEST(SimulatedArm, RefusesOptionsThatMakeNoArm)
{
    SimulatedArmOptions o;
    o.arm.mass_kg = -1;
    try {
        SimulatedArm arm(o);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("mass_kg"), std::string::npos) << e.what();
    }
    o = {};
    o.hand.period_s = 0;
    EXPECT_THROW(SimulatedArm{o}, std::invalid_argument);
    o = {};
    o.max_force_N = std::nan("");
    EXPECT_THROW(SimulatedArm{o}, std::invalid_argument);
}

}  // namespace
}  // namespace echosim::device

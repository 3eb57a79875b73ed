// The haptic loop lets go of the hand when it stops (issue 34, signals): whatever ends a session,
// the last force the device was sent is zero, whether the loop ran on its own thread or in
// lock-step. The device here records what it is sent, from whichever thread sends it.
#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "device/held_device.hpp"
#include "haptics/haptic_loop.hpp"
#include "physics/physics_fixture.hpp"

namespace echosim::haptics {
namespace {

// A hand holding the probe 6 mm into the middle of the patch, for ever (world poses, as a scripted
// trajectory gives them), that remembers the last force it was sent (device::HeldDevice, held there).
std::shared_ptr<device::HeldDevice> pressing_hand()
{
    return std::make_shared<device::HeldDevice>(pressed_along_beam(test::leg().probe_rest_pose(0.5f, 0.5f), 6.0), "pressing hand");
}

TEST(HapticStop, TheLastForceSentIsZeroAfterALockStepRun)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    auto hand = pressing_hand();
    HapticLoop loop(physics, hand, mapping);
    for (int i = 1; i <= 300; ++i) {
        loop.tick(i * 1e-3);
        physics.step_to(i * 1e-3);
    }
    ASSERT_GT(hand->last_force_N(), 1.0) << "6 mm into the thigh pushes back";
    loop.stop();
    EXPECT_EQ(hand->last_force_N(), 0.0);
}

TEST(HapticStop, TheLastForceSentIsZeroAfterTheThreadStops)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    auto hand = pressing_hand();
    HapticLoop loop(physics, hand, mapping, HapticOptions{.realtime_priority = false});
    for (int i = 1; i <= 300; ++i) {  // into contact: the physics' contact model is then the pressed one
        loop.tick(i * 1e-3);
        physics.step_to(i * 1e-3);
    }
    loop.start();  // the physics holds its last model; the loop renders it, 6 mm in, every tick
    const long before = hand->writes();
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (hand->writes() < before + 50 && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_GE(hand->writes(), before + 50) << "the loop's thread did not tick";
    ASSERT_GT(hand->last_force_N(), 1.0);
    loop.stop();
    EXPECT_EQ(hand->last_force_N(), 0.0);
    const long after_stop = hand->writes();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(hand->writes(), after_stop) << "a force was sent after the stop";
}

}  // namespace
}  // namespace echosim::haptics

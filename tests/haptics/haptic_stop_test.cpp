// The haptic loop lets go of the hand when it stops (issue 34, signals): whatever ends a session,
// the last force the device was sent is zero, whether the loop ran on its own thread or in
// lock-step. The device here records what it is sent, from whichever thread sends it.
#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "haptics/haptic_loop.hpp"
#include "physics/physics_fixture.hpp"

namespace echosim::haptics {
namespace {

// A hand holding the probe 6 mm into the middle of the patch, for ever (world poses, as a scripted
// trajectory gives them), that remembers the last force it was sent.
class PressingHand : public device::Device {
public:
    PressingHand()
    {
        caps_.name = "pressing hand";
        caps_.driver = "test";
        caps_.control = device::Control::world;
        caps_.max_force_N = 20;
        const Pose p = pressed_along_beam(test::leg().probe_rest_pose(0.5f, 0.5f), 6.0);
        sample_.control = device::Control::world;
        sample_.connected = true;
        sample_.position = {p.position.x, p.position.y, p.position.z};
        sample_.orientation = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized();
    }
    const device::Capabilities& capabilities() const override { return caps_; }
    bool read(double, device::DeviceSample& out) noexcept override
    {
        ++sample_.sequence;
        out = sample_;
        return true;
    }
    void write_force(const Eigen::Vector3d& f) noexcept override
    {
        last_N_.store(f.norm());
        writes_.fetch_add(1);
    }
    void events(std::vector<device::DeviceEvent>&) override {}

    double last_force_N() const { return last_N_.load(); }
    long writes() const { return writes_.load(); }

private:
    device::Capabilities caps_;
    device::DeviceSample sample_;
    std::atomic<double> last_N_{-1};
    std::atomic<long> writes_{0};
};

TEST(HapticStop, TheLastForceSentIsZeroAfterALockStepRun)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    auto hand = std::make_shared<PressingHand>();
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
    auto hand = std::make_shared<PressingHand>();
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

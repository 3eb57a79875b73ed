// The haptic loop against the physics it renders (engine/haptics): the local model's force at a
// refresh against the full model's, the force's continuity, its limits, the probe's mapping, and a
// loop that neither waits for a stalled physics nor allocates.
#include "haptics/haptic_loop.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "device/null_device.hpp"
#include "device/scripted_device.hpp"
#include "counting_new.hpp"
#include "physics/physics_fixture.hpp"

namespace echosim::haptics {
namespace {

Eigen::Vector3d eigen(glm::vec3 v) { return {v.x, v.y, v.z}; }

device::TrajectoryRow row(double t, const Pose& p)
{
    return {t, eigen(p.position), Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized()};
}

// down onto the patch centre at 20 mm/s from 2 mm above to 6 mm in, hold, then slide around the thigh
device::Trajectory press_and_slide()
{
    const scene::LegModel& leg = test::leg();
    std::vector<device::TrajectoryRow> rows;
    for (int i = 0; i <= 400; ++i) rows.push_back(row(i * 1e-3, pressed_along_beam(leg.probe_rest_pose(0.5f, 0.5f), -2.0 + 0.02 * i)));
    for (int i = 1; i <= 600; ++i) rows.push_back(row(0.4 + i * 1e-3, pressed_along_beam(leg.probe_rest_pose(0.5f, 0.5f + 1.5e-4f * float(i)), 6.0)));
    return device::Trajectory::parse(device::format_trajectory(rows), "press and slide");
}

physics::PhysicsOptions refreshing_at(int steps_per_publish)
{
    physics::PhysicsOptions o;
    o.steps_per_publish = steps_per_publish;
    return o;
}

TEST(HapticLoop, LocalModelMatchesTheFullModelAtEachRefreshAndTheForceStaysContinuous)
{
    physics::PhysicsRunner physics(test::shipped_model(7), refreshing_at(10));  // the physics at 100 Hz
    const ProbeMapping mapping(test::leg());
    HapticLoop loop(physics, std::make_shared<device::ScriptedDevice>(press_and_slide(), "script"), mapping);
    std::int64_t seen_step = 0;
    double last_force = 0;
    int refreshes = 0;
    for (int i = 1; i <= 1000; ++i) {
        const double t = i * 1e-3;
        loop.tick(t);
        physics.step_to(t);
        const HapticSample& s = loop.latest();
        if (s.physics_step != seen_step && s.physics_force_N > 0.5) {
            // the new model at the probe's pose now, against the full model's force at the step
            // it came from, up to 1 ms of motion later
            EXPECT_NEAR(s.model_force_N, s.physics_force_N, 0.05 * s.physics_force_N) << "at " << t << " s";
            ++refreshes;
        }
        seen_step = s.physics_step;
        // 20 mm/s into tissue of a few N/mm: a few hundredths of a newton a millisecond, never a step
        EXPECT_LT(std::abs(s.force.along_N - last_force), 0.1) << "at " << t << " s";
        last_force = s.force.along_N;
    }
    EXPECT_GT(refreshes, 60);
    EXPECT_GT(last_force, 2.0);  // pressed 6 mm in
}

TEST(HapticLoop, KeepsItsRateWhileThePhysicsIsStalled)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    std::atomic<bool> stall{false}, stalled{false};
    physics.set_after_step([&](std::int64_t) {
        while (stall.load()) {
            stalled = true;
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    });
    const ProbeMapping mapping(test::leg());
    HapticOptions o;
    o.realtime_priority = false;
    HapticLoop loop(physics, std::make_shared<device::NullDevice>(), mapping, o);
    physics.start();
    loop.start();
    EXPECT_FALSE(loop.cpus_awake()) << "a best-effort loop asked to keep the CPUs awake";
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    stall = true;
    while (!stalled) std::this_thread::yield();
    const std::int64_t steps = physics.stats().steps, ticks = loop.ticks();
    std::this_thread::sleep_for(std::chrono::seconds(1));
    const std::int64_t ticked = loop.ticks() - ticks;
    EXPECT_EQ(physics.stats().steps, steps) << "the physics was meant to be stalled";
    // 1000 at 1 kHz; a loop waiting for the physics would have made none (the margin is for a busy CI)
    EXPECT_GT(ticked, 500) << "the loop ticked " << ticked << " times in the second the physics stood still";
    stall = false;
    loop.stop();
    physics.stop();
}

// A real-time loop holds the wake-latency request while it runs, or says why it cannot, naming the file.
TEST(HapticLoop, KeepsTheCpusAwakeWhileRunningOrSaysWhyNot)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    HapticLoop loop(physics, std::make_shared<device::NullDevice>(), mapping);
    EXPECT_FALSE(loop.cpus_awake());
    loop.start();
    // held (as root, or where a udev rule grants the file), or the note names the file and why not
    const bool named = loop.priority_note().find(CpuWakeLatency::kDevice) != std::string::npos;
    EXPECT_NE(loop.cpus_awake(), named) << loop.priority_note();
    if (::access(CpuWakeLatency::kDevice, F_OK) != 0) {
        EXPECT_FALSE(loop.cpus_awake()) << "held a request through no file";
    }
    loop.stop();
    EXPECT_FALSE(loop.cpus_awake()) << "the request outlived the loop";
}

// The loop's latest tick is kept taken apart (PeriodStats::worst), so a stall names its part: here a
// driver whose read blocks once for 150 ms (far longer than anything this machine does to the loop
// otherwise) is named as the tick before the latest start, and the ticks before it are kept. No
// timing is judged: the stall's own length is a lower bound on what must be seen.
TEST(HapticLoop, ItsLatestTickIsKeptTakenApartAndNamesAStalledRead)
{
    struct StallingDevice : device::NullDevice {
        std::atomic<int> reads{0};
        std::atomic<bool> stalled{false};
        bool read(double t_s, device::DeviceSample& out) noexcept override
        {
            if (++reads == 300) {
                std::this_thread::sleep_for(std::chrono::milliseconds(150));
                stalled = true;
            }
            return NullDevice::read(t_s, out);
        }
    };
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    const auto device = std::make_shared<StallingDevice>();
    HapticLoop loop(physics, device, mapping);  // real time where permitted
    loop.start();
    while (!device->stalled || loop.ticks() < 500) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    loop.stop();
    const PeriodStats s = loop.stats();
    const WorstTick& w = s.worst;
    EXPECT_NEAR(w.late_ms, s.window_max_late_ms, 1e-9) << "the worst tick is not the latest start";
    EXPECT_GE(w.late_ms, 140.0);
    EXPECT_EQ(w.tick, 301) << "the tick after the stalled read";
    EXPECT_GE(w.read_us, 150'000.0) << "the stall not put on the device's read";
    EXPECT_LT(w.force_us + w.write_us + w.handoff_us, w.read_us);
    EXPECT_FALSE(w.slept) << "a loop 150 ms behind slept";
    EXPECT_GE(w.spell_ms, 150.0);
    EXPECT_GE(w.voluntary_switches, 1) << "the read slept: the thread was switched out";
    EXPECT_GE(w.ran_ms, 0.0);
    EXPECT_LT(w.ran_ms, w.spell_ms) << "the thread ran through a sleep";
    EXPECT_GE(w.cpu_before, 0);
    EXPECT_GE(w.cpu_after, 0);
    EXPECT_GT(w.at_s, 0.25);
    EXPECT_GT(w.monotonic_s, 0.0);
    // the ticks before it ran on time, give or take this machine: none of them held the stall
    for (float late : w.late_before_us) EXPECT_LT(late, 0.5 * w.late_ms * 1000.0);
}

TEST(HapticLoop, ATickAllocatesNothing)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    HapticLoop loop(physics, std::make_shared<device::ScriptedDevice>(press_and_slide(), "script"), mapping);
    for (int i = 1; i <= 300; ++i) {  // into contact
        loop.tick(i * 1e-3);
        physics.step_to(i * 1e-3);
    }
    const long before = test::allocations();
    for (int i = 301; i <= 1300; ++i) loop.tick(i * 1e-3);
    EXPECT_EQ(test::allocations() - before, 0);
}

// The same for the running loop's own thread: its waits, its bookkeeping and the worst tick's record
// (getrusage, sched_getcpu, the clock) allocate nothing either, over a thousand ticks.
TEST(HapticLoop, TheRunningLoopAllocatesNothing)
{
    physics::PhysicsRunner physics(test::shipped_model(3), physics::PhysicsOptions{});  // not stepping: its thread would count
    const ProbeMapping mapping(test::leg());
    HapticLoop loop(physics, std::make_shared<device::NullDevice>(), mapping);
    loop.start();
    while (loop.ticks() < 50) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const long before = test::allocations();
    const std::int64_t ticks = loop.ticks();
    while (loop.ticks() < ticks + 1000) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const long made = test::allocations() - before;
    loop.stop();
    EXPECT_EQ(made, 0);
    EXPECT_GE(loop.stats().worst.late_ms, 0.0) << "no worst tick kept";
}

TEST(HapticLoop, ADeviceThatGoesAwayOrSendsNaNDoesNotStopIt)
{
    struct Flaky : device::Device {
        device::Capabilities caps;
        int reads = 0;
        const device::Capabilities& capabilities() const override { return caps; }
        bool read(double, device::DeviceSample& s) noexcept override
        {
            ++reads;
            s.control = device::Control::world;
            s.connected = reads < 10;
            s.position = reads < 20 ? Eigen::Vector3d(0, 0, 0) : Eigen::Vector3d(std::nan(""), 0, 0);
            return s.connected;
        }
        void write_force(const Eigen::Vector3d&) noexcept override {}
        void events(std::vector<device::DeviceEvent>&) override {}
    };
    physics::PhysicsRunner physics(test::shipped_model(1), physics::PhysicsOptions{});
    const ProbeMapping mapping(test::leg());
    HapticLoop loop(physics, std::make_shared<Flaky>(), mapping);
    for (int i = 1; i <= 30; ++i) loop.tick(i * 1e-3);
    EXPECT_EQ(loop.ticks(), 30);
    EXPECT_FALSE(loop.latest().device.connected);
    EXPECT_EQ(physics.stats().refused_commands, 11);  // the NaN poses, refused and counted by the physics
}

TEST(ForceLaw, StiffnessDampingAndForceWithinTheDevicesLimits)
{
    physics::LocalContactModel m;
    m.in_contact = true;
    m.axis = Eigen::Vector3d(0, 0, 1);
    m.force = 2.0;
    m.stiffness = 10.0;
    m.damping = 0.5;
    const ForceLimits limits{5.0, 2.0, 0.1};
    const HapticForce a = local_model_force(m, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 10), limits);
    EXPECT_DOUBLE_EQ(a.along_N, 2.0 + 2.0 * 1.0 + 0.1 * 10.0);  // both cut to the device's
    EXPECT_TRUE(a.clamped);
    EXPECT_EQ(a.world_N, Eigen::Vector3d(0, 0, -5.0));  // pushes the probe back out
    const HapticForce b = local_model_force(m, Eigen::Vector3d(0, 0, 3), Eigen::Vector3d::Zero(), limits);
    EXPECT_DOUBLE_EQ(b.along_N, 5.0);  // 8 N cut to the largest force
    const HapticForce free = local_model_force(m, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d::Zero(), ForceLimits{});
    EXPECT_DOUBLE_EQ(free.along_N, 12.0);
    EXPECT_FALSE(free.clamped);
    m.in_contact = false;
    EXPECT_EQ(local_model_force(m, Eigen::Vector3d(0, 0, 9), Eigen::Vector3d::Zero(), limits).along_N, 0.0);
    EXPECT_EQ(held_physics_force(m, limits).along_N, 0.0);
}

TEST(ForceLaw, ARefreshFadesOutOverOnePhysicsPeriod)
{
    RefreshBlend b;
    EXPECT_EQ(b.apply(4.0, 0.0), 4.0);  // nothing to fade yet
    b.refresh(1.0, 3.0, 2.0, 0.01);     // the new model says 2 N where the old said 3 N
    EXPECT_DOUBLE_EQ(b.apply(2.0, 1.0), 3.0);
    EXPECT_NEAR(b.apply(2.0, 1.005), 2.5, 1e-12);
    EXPECT_DOUBLE_EQ(b.apply(2.0, 1.01), 2.0);
    EXPECT_DOUBLE_EQ(b.apply(2.0, 2.0), 2.0);
    b.refresh(2.0, 2.0, 2.0, 0.01);
    b.refresh(2.005, 2.0, 1.0, 0.01);  // mid-fade: from what was rendered
    EXPECT_DOUBLE_EQ(b.apply(1.0, 2.005), 2.0);
    EXPECT_DOUBLE_EQ(b.apply(0.0, 2.1), 0.0);  // never pulls
}

TEST(ProbeMapping, PlacesTheProbeOverTheSkinAndMapsAnArmsWorkspace)
{
    const scene::LegModel& leg = test::leg();
    const ProbeMapping mapping(leg);
    device::DeviceSample s;
    s.control = device::Control::surface;
    s.surface = {0.3, 0.6, 0.2, 0.0, 5.0};
    const ProbeFace f = mapping.face(s);
    const Pose rest = leg.probe_rest_pose(0.3f, 0.6f);
    const Eigen::Vector3d rest_beam = eigen(rest.axis_y()), lateral = eigen(rest.axis_x());
    EXPECT_NEAR(std::acos(std::clamp(f.beam().dot(rest_beam), -1.0, 1.0)), 0.2, 1e-5);  // fanned 0.2 rad
    EXPECT_NEAR(f.beam().dot(lateral), 0.0, 1e-6);                                         // about the array
    EXPECT_LT((f.position - (eigen(rest.position) + 5.0 * f.beam())).norm(), 1e-4);        // pressed along the tilted beam

    device::DeviceSample arm;
    arm.control = device::Control::workspace;  // the handle upright at the workspace origin
    const ProbeFace a = mapping.face(arm);
    const Pose centre = leg.probe_rest_pose(0.5f, 0.5f);
    EXPECT_LT((a.position - (eigen(centre.position) - 20.0 * eigen(centre.axis_y()))).norm(), 1e-4);
    EXPECT_NEAR(a.beam().dot(eigen(centre.axis_y())), 1.0, 1e-6);
    arm.position = Eigen::Vector3d(0, -30, 0);  // the handle 30 mm down: 10 mm into the skin
    EXPECT_LT((mapping.face(arm).position - (eigen(centre.position) + 10.0 * eigen(centre.axis_y()))).norm(), 1e-4);
    // the tissue pushing the probe back out is the handle pushed up (+y in the device's frame)
    const Eigen::Vector3d up = mapping.to_device(-eigen(centre.axis_y()), device::Control::workspace);
    EXPECT_LT((up - Eigen::Vector3d(0, 1, 0)).norm(), 1e-6);
}

// Surface devices over the whole course: the limits reach from above the groin crease to below
// the trifurcation along the limb and once around it (the same skin point at both ends of v), and
// a quarter twist turns the array from across the limb to along it (a longitudinal view); the
// twist comes before the fan, which then sweeps across the limb.
TEST(ProbeMapping, SurfaceDevicesReachTheWholeCourseAndTurnLongitudinal)
{
    const scene::LegModel& leg = test::leg();
    const ProbeMapping mapping(leg);
    const device::SurfaceLimits limits = exam_limb_surface(leg);
    EXPECT_NEAR(leg.probe_rest_pose(float(limits.u_lo), 0.5f).position.z, kExamLimbFromZ_mm, 2.0f);
    EXPECT_NEAR(leg.probe_rest_pose(float(limits.u_hi), 0.5f).position.z, kExamLimbToZ_mm, 2.0f);
    EXPECT_LT(limits.u_lo, 0.0);
    EXPECT_GT(limits.u_hi, 1.0);
    EXPECT_LT(glm::distance(leg.probe_rest_pose(0.5f, float(limits.v_lo)).position, leg.probe_rest_pose(0.5f, float(limits.v_hi)).position),
              0.5f);
    EXPECT_GT(glm::distance(leg.probe_rest_pose(0.5f, float(limits.v_lo)).position, leg.probe_rest_pose(0.5f, 0.5f).position), 50.0f)
        << "the ends of v are the far side of the limb";

    device::DeviceSample s;
    s.control = device::Control::surface;
    s.surface.u = 2.0;  // past the patch, down the thigh
    s.surface.twist_rad = std::numbers::pi / 2;
    const Pose rest = leg.probe_rest_pose(2.0f, 0.5f);
    const Eigen::Vector3d along = eigen(leg.probe_rest_pose(2.05f, 0.5f).position - leg.probe_rest_pose(1.95f, 0.5f).position).normalized();
    ProbeFace f = mapping.face(s);
    EXPECT_LT((f.position - eigen(rest.position)).norm(), 1e-4);
    EXPECT_GT(std::abs((f.orientation * Eigen::Vector3d::UnitX()).dot(along)), 0.99) << "the array along the limb";
    EXPECT_NEAR(f.beam().dot(eigen(rest.axis_y())), 1.0, 1e-6) << "the beam still into the skin";
    s.surface.fan_rad = 0.2;
    const ProbeFace fanned = mapping.face(s);
    // the turned array lies along the rest pose's elevational axis: the fan keeps the beam square to it
    EXPECT_NEAR(fanned.beam().dot(eigen(rest.axis_z())), 0.0, 1e-5) << "the fan of a turned probe sweeps across the limb";
    EXPECT_NEAR(std::abs(fanned.beam().dot(eigen(rest.axis_x()))), std::sin(0.2), 0.01);
}

}  // namespace
}  // namespace echosim::haptics

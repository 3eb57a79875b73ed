#include "physics/physics_runner.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "physics/physics_fixture.hpp"
#include "physics/probe_sweep.hpp"
#include "physics/simulation.hpp"
#include "core/triple_buffer.hpp"

namespace echosim::physics {
namespace {

TEST(TripleBuffer, ReaderSeesTheLatestWholeValue)
{
    TripleBuffer<std::array<int, 64>> buffer;
    std::atomic<bool> done{false};
    std::thread writer([&] {
        for (int k = 1; k <= 200000; ++k) {
            auto& slot = buffer.write_slot();
            slot.fill(k);  // a torn read would mix two values
            buffer.publish();
        }
        done = true;
    });
    int last = 0;
    while (!done.load()) {
        const auto& v = buffer.read();
        for (int x : v) ASSERT_EQ(x, v[0]) << "torn value";
        ASSERT_GE(v[0], last) << "went back in time";
        last = v[0];
    }
    writer.join();
    EXPECT_EQ(buffer.read()[0], 200000) << "the last value published is what the reader gets";
}

TEST(PhysicsRunner, LockStepMatchesSteppingByHand)
{
    const tissue::TissueModel m = test::shipped_model(2);
    PhysicsOptions o;
    o.clear_stride = 1;  // by hand is a time step at a time (strides: the test after this one)
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    const ProbeCommand c = contact::probe_at(pressed_along_beam(rest, 6.0));

    PhysicsRunner runner(m, o);
    runner.command(c);
    runner.step_to(0.1);  // the probe enters from 30 mm behind its face at 0.5 mm a step (probe_sweep.hpp)
    const SurfaceSnapshot& snap = runner.latest();
    EXPECT_EQ(snap.step, 100);

    // by hand, on the runner's own compiled model
    Simulation sim(runner.compiled());
    TissueState& s = sim.state;
    for (int i = 0; i < 100; ++i) {
        s.probe = swept_probe(s.probe, c, o.time_step);
        sim.step();
    }
    for (Eigen::Index i = 0; i < s.x.size(); ++i) ASSERT_EQ(snap.positions[std::size_t(i)], float(s.x[i]));
    EXPECT_DOUBLE_EQ(snap.probe_force_N, s.last.probe_force_N);
    EXPECT_GT(snap.probe_force_N, 0.5);

    // the haptic thread's hand-off: the local model of that same step
    const LocalContactModel& local = runner.latest_contact();
    const LocalContactModel expected = local_contact_model(*sim.model, s);
    EXPECT_EQ(local.step, 100);
    EXPECT_TRUE(local.in_contact);
    EXPECT_DOUBLE_EQ(local.force, s.last.probe_force_N);
    EXPECT_DOUBLE_EQ(local.stiffness, expected.stiffness);
    EXPECT_EQ(local.face, c.position);
}

// PhysicsOptions::clear_stride: a probe lowered from 15 mm above the skin at 20 mm/s, pressed 6 mm
// and held. While it is clear of the skin the lock-step physics covers four time steps a step; the
// touch and the press are stepped at 1 kHz, so the force the press settles to is the one of a
// run that never strides (the tissue at rest either way before the touch), and every step_to ends
// where it was asked, on the time-step grid.
TEST(PhysicsRunner, WhileTheProbeIsClearOfTheSkinAStepCoversSeveralTimeSteps)
{
    const tissue::TissueModel m = test::shipped_model(2);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    PhysicsOptions fine;
    fine.clear_stride = 1;
    PhysicsRunner strided(m, PhysicsOptions{}), stepped(m, fine);
    ASSERT_EQ(strided.compiled()->options.clear_stride, 4);
    const double h = fine.time_step;
    std::int64_t strides_at_touch = -1;
    for (int ms = 5; ms <= 1600; ms += 5) {  // commands every 5 ms, as a device's would come
        const double press = std::min(6.0, -15.0 + 0.02 * ms);
        for (PhysicsRunner* r : {&strided, &stepped}) {
            r->command(contact::probe_at(pressed_along_beam(rest, press)));
            r->step_to(ms * h);
            ASSERT_NEAR(r->latest().time, ms * h, 1e-9);
            ASSERT_EQ(r->latest().step, ms);
        }
        if (strides_at_touch < 0 && strided.latest().contacts > 0) {
            strides_at_touch = strided.stats().strides;
            // the first touch comes at a time step of its own, as the stepped run's does
            EXPECT_NEAR(strided.latest().probe_force_N, stepped.latest().probe_force_N, 0.05);
        }
    }
    // clear for the first 0.7 s or so (15 mm at 20 mm/s, less the clearance): some 170 strides
    EXPECT_GT(strides_at_touch, 100);
    EXPECT_EQ(strided.stats().strides, strides_at_touch) << "a stride while the probe touched the skin";
    EXPECT_EQ(stepped.stats().strides, 0);
    EXPECT_EQ(strided.stats().steps, 1600);
    EXPECT_GT(stepped.latest().probe_force_N, 1.0);
    EXPECT_NEAR(strided.latest().probe_force_N, stepped.latest().probe_force_N, 1e-3 * stepped.latest().probe_force_N);
}

// The force on a probe pressed `press_mm` into the skin at `rest` over 0.2 s and held to 0.6 s.
double force_pressed_by_a_ramp(const tissue::TissueModel& m, const Pose& rest, double press_mm)
{
    PhysicsRunner runner(m, PhysicsOptions{});
    for (int ms = 1; ms <= 600; ++ms) {
        runner.command(contact::probe_at(pressed_along_beam(rest, press_mm * std::min(1.0, ms / 200.0))));
        runner.step_to(ms * 1e-3);
    }
    return runner.latest().probe_force_N;
}

// Issue 34: a probe commanded 25 mm into the leg at once (a trajectory's first pose) gave 0 N: the
// skin it jumped past met its sides, not its face. Swept in, it meets the face: the force is the
// one the same press reaches by a ramp, within 2 %.
TEST(PhysicsRunner, AProbeThatStartsDeepInTheLegPushesAsOneThatPressedThere)
{
    const tissue::TissueModel m = test::shipped_model(3);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    const ProbeCommand deep = contact::probe_at(pressed_along_beam(rest, 25.0));

    PhysicsRunner jumped(m, PhysicsOptions{});
    jumped.command(deep);
    jumped.step_to(0.6);

    const double ramped = force_pressed_by_a_ramp(m, rest, 25.0);
    EXPECT_GT(ramped, 10.0);
    EXPECT_NEAR(jumped.latest().probe_force_N, ramped, 0.02 * ramped);

    // and a jump across the skin, pressed, is swept too: 40 mm sideways in one command
    const Pose beside = test::leg().probe_rest_pose(0.5f, 0.8f);
    jumped.command(contact::probe_at(pressed_along_beam(beside, 10.0)));
    jumped.step_to(1.2);
    const double there = force_pressed_by_a_ramp(m, beside, 10.0);
    EXPECT_GT(there, 3.0);
    EXPECT_NEAR(jumped.latest().probe_force_N, there, 0.05 * there);
}

// The sweep itself: a probe that appears enters from kProbeEntryMm behind its face, no point of
// the face moves more than kMaxProbeMoveMm a step, and each swept step's velocity is its motion.
TEST(ProbeSweep, EntersFromBehindAndNeverMovesMoreThanItsStep)
{
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    const ProbeCommand target = contact::probe_at(pressed_along_beam(rest, 5.0));
    contact::ProbeState p;  // inactive
    p = swept_probe(p, target, 1e-3);
    const Eigen::Vector3d axis = target.orientation.normalized() * Eigen::Vector3d::UnitY();
    EXPECT_NEAR((target.position - p.position).dot(axis), kProbeEntryMm - kMaxProbeMoveMm, 1e-9);
    EXPECT_NEAR(p.velocity.dot(axis), kMaxProbeMoveMm / 1e-3, 1e-6);
    int steps = 1;
    while (p.position != target.position && steps < 1000) {
        const contact::ProbeState before = p;
        p = swept_probe(p, target, 1e-3);
        EXPECT_LE((p.position - before.position).norm(), kMaxProbeMoveMm + 1e-12);
        ++steps;
    }
    EXPECT_LE(std::abs(steps - kProbeEntryMm / kMaxProbeMoveMm), 1.0);  // 60, or 61 for the last rounding
    EXPECT_EQ(p.velocity, target.velocity);  // arrived: the command's own
    // a turn of 90 degrees about the beam sweeps the array's ends by pi/2 x 20 mm: 63 steps
    ProbeCommand turned = target;
    turned.orientation = target.orientation * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
    steps = 0;
    while (!p.orientation.isApprox(turned.orientation, 1e-12) && steps < 1000) p = swept_probe(p, turned, 1e-3), ++steps;
    EXPECT_LE(std::abs(steps - M_PI / 2 * 20.0 / kMaxProbeMoveMm), 1.0);
    // an inactive command lifts the probe at once
    ProbeCommand lifted;
    EXPECT_FALSE(swept_probe(p, lifted, 1e-3).active);
}

TEST(PhysicsRunner, RefusesACommandThatIsNotAPoseAndKeepsTheLastGoodOne)
{
    const tissue::TissueModel m = test::shipped_model(2);
    const Pose rest = test::leg().probe_rest_pose(0.5f, 0.5f);
    const ProbeCommand good = contact::probe_at(pressed_along_beam(rest, 6.0));
    PhysicsRunner runner(m, PhysicsOptions{});
    EXPECT_TRUE(runner.command(good));
    runner.step_to(0.02);

    ProbeCommand bad = good;
    bad.position.y() = std::nan("");
    EXPECT_EQ(probe_command_error(bad), "position is not finite");
    EXPECT_FALSE(runner.command(bad));
    bad = good;
    bad.orientation.coeffs() *= 2.0;
    EXPECT_NE(probe_command_error(bad).find("not a rotation"), std::string::npos);
    EXPECT_FALSE(runner.command(bad));
    bad = good;
    bad.velocity.x() = std::numeric_limits<double>::infinity();
    EXPECT_EQ(probe_command_error(bad), "velocity is not finite");
    EXPECT_FALSE(runner.command(bad));

    runner.step_to(0.05);
    EXPECT_EQ(runner.stats().refused_commands, 3);
    EXPECT_EQ(runner.latest().resets, 0);
    EXPECT_GT(runner.latest().probe_force_N, 0.5);  // still pressed by the good command
}

TEST(PhysicsRunner, LockStepGivesExactlyNStepsForNTimeSteps)
{
    // step_to(N h) takes exactly N steps, however the sum of N time steps rounds
    const auto model = compile_model(test::shipped_model(1), PhysicsOptions{});
    const double h = model->options.time_step;
    PhysicsRunner runner(model);
    EXPECT_EQ(runner.compiled(), model);  // shared, not copied
    std::int64_t total = 0;
    for (int n : {1, 7, 100, 293}) {
        total += n;
        runner.step_to(double(total) * h);
        EXPECT_EQ(runner.latest().step, total) << "to " << total << " h";
        EXPECT_EQ(runner.stats().steps, total);
        EXPECT_NEAR(runner.latest().time, double(total) * h, 1e-9);
        EXPECT_EQ(runner.latest_contact().step, total);
        runner.step_to(double(total) * h);  // already there: no further step
        EXPECT_EQ(runner.stats().steps, total);
    }
}

TEST(PhysicsRunner, ThreadStepsPublishesAndStops)
{
    // what the real-time thread must do, whatever the machine's speed: it steps, the snapshots it
    // publishes move forward in step and time, and it stops cleanly, after which lock-step goes on
    // from where it stopped. (How fast it keeps up is the benchmarks' business.)
    const tissue::TissueModel m = test::shipped_model(1);
    PhysicsRunner runner(m, PhysicsOptions{});
    const double h = runner.compiled()->options.time_step;
    for (int round = 0; round < 2; ++round) {  // a stopped runner starts again
        const std::int64_t start = runner.latest().step;
        runner.start();
        EXPECT_THROW(runner.step_to(1.0), std::logic_error) << "no lock-step while the thread owns the state";
        // a bound against a hung thread, far beyond any machine's pace: not a timing assertion
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        std::int64_t last = start;
        int fresh = 0;
        while (fresh < 5 && std::chrono::steady_clock::now() < give_up) {
            const SurfaceSnapshot& snap = runner.latest();
            ASSERT_GE(snap.step, last) << "a snapshot went back in time";
            if (snap.step > last) {
                ++fresh;
                last = snap.step;
                EXPECT_NEAR(snap.time, double(snap.step) * h, 1e-9);
                EXPECT_EQ(snap.positions.size(), 3 * m.node_count());
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        runner.stop();
        EXPECT_EQ(fresh, 5) << "the thread published no new snapshots";
        runner.stop();  // twice is harmless

        // stopped: the last snapshot is the last step, and nothing steps any more but lock-step
        const std::int64_t steps = runner.stats().steps;
        EXPECT_GE(steps, last);
        EXPECT_EQ(runner.latest().step, steps);
        EXPECT_EQ(runner.latest_contact().step, steps);
        runner.step_to(runner.latest().time + 10 * h);
        EXPECT_EQ(runner.stats().steps, steps + 10);
        EXPECT_EQ(runner.latest().step, steps + 10);
    }
    EXPECT_EQ(runner.latest().resets, 0);
}

}  // namespace
}  // namespace echosim::physics

// The exam window (session/session.hpp, "The exam window"): the tissue simulation follows the probe
// over the whole exam, from the groin to the knee, and a press anywhere pushes back as a press on
// the home patch (the fitted thigh) does.
#include "session/session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "device/held_device.hpp"
#include "device/mouse_keyboard_device.hpp"
#include "device/scripted_device.hpp"
#include "haptics/probe_mapping.hpp"
#include "session/simulation_model.hpp"

namespace echosim::session {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;
const double kStep = SessionOptions{}.physics.time_step;

// The window moves the fitted thigh's parameters with it, and they scatter by about +-20 % from
// one sample point to the next (the fit's noise: assets/models/thigh.json); the leg's curvature
// under the 40 mm face differs from the groin to the knee. A press anywhere is held to within this
// share of the same press at the home patch's centre.
constexpr double kForceTolerance = 0.25;

// a session whose window follows the probe (SessionOptions::window_follows_probe)
SessionOptions following()
{
    SessionOptions o;
    o.window_follows_probe = true;
    return o;
}

// the probe resting transversely on the skin at height z [mm], angle theta, of the exam limb
Pose rest_at(const Session& s, float z, float theta)
{
    const scene::LegModel& leg = s.leg();
    return leg.limb_rest_pose({leg.limb_t_at_z(z), theta});
}

// the home patch's centre angle, the anterior-medial thigh over the femoral vessels
float home_theta() { return scene::LegModel{}.patch().centre_theta(); }

// the settled push of a press of `press_mm` on the home patch's centre [N]
double home_force(double press_mm)
{
    Session s;
    const SettleReport r = s.press_and_settle(s.leg().probe_rest_pose(0.5f, 0.5f), press_mm);
    EXPECT_TRUE(r.settled);
    return r.force_N;
}

// lifts the probe 5 mm off the skin where it rests and lets the tissue come back for 0.05 s
void lift(Session& s)
{
    s.place_probe({pressed_along_beam(s.probe().rest, -5.0), 0.0});
    for (int i = 0; i < 50; ++i) s.advance(kStep);
}

// whether the window's skin covers height z (its first and last rings' planes)
bool window_covers(const Session& s, float z)
{
    const scene::ExamPatch& w = s.window();
    const float top = s.leg().limb_point({w.t0, w.centre_theta()}).z, bottom = s.leg().limb_point({w.t1, w.centre_theta()}).z;
    return z <= top && z >= bottom;
}

TEST(ExamWindow, StartsOnTheHomePatch)
{
    Session s(following());
    EXPECT_EQ(s.window_serial(), 0);
    EXPECT_EQ(s.window().cells, scene::LegModel{}.patch().cells);
    const SessionView& v = s.view();
    EXPECT_FALSE(v.in_contact);
    EXPECT_TRUE(v.over_model) << "the probe starts on the patch centre";
    EXPECT_EQ(v.window_serial, 0);
}

// The three sites of the extended exam the home patch does not reach: each press moves the window
// there first (the probe comes down lifted), then pushes back as the home press does.
TEST(ExamWindow, PressesAtTheGroinTheCanalAndBehindTheKneePushBackAsAtHome)
{
    const double press = 8.0;
    const double reference = home_force(press);
    ASSERT_GT(reference, 2.0);
    struct Site {
        const char* name;
        float z, theta;
    };
    // CFV at the groin crease, the FV in the adductor canal, the popliteal vein from behind the
    // knee (posterior-medial: the leg turned out)
    for (const Site site : {Site{"groin", 0.0f, home_theta()}, Site{"adductor canal", -300.0f, home_theta()},
                            Site{"popliteal fossa", -450.0f, 45.0f * kDeg}}) {
        SCOPED_TRACE(site.name);
        Session s(following());
        const SettleReport r = s.press_and_settle(rest_at(s, site.z, site.theta), press);
        ASSERT_TRUE(r.settled);
        EXPECT_EQ(s.window_serial(), 1) << "moved once, before the press";
        EXPECT_TRUE(window_covers(s, site.z));
        const SessionView& v = s.view();
        EXPECT_TRUE(v.in_contact);
        EXPECT_TRUE(v.over_model);
        EXPECT_EQ(v.window_serial, 1);
        EXPECT_EQ(v.patch->size(), s.leg().patch().rest.vertices.size());
        EXPECT_NEAR(r.force_N, reference, kForceTolerance * reference);
    }
}

// The extended exam's walk down the thigh: a press every 2 cm from the groin to the adductor
// canal, the probe lifted between presses. The window follows, and every press meets tissue.
TEST(ExamWindow, SlidingFromTheGroinToTheCanalWithLiftsFollowsTheProbe)
{
    const double press = 6.0;
    const double reference = home_force(press);
    Session s(following());
    const float theta = home_theta();
    for (float z = 0.0f; z >= -300.0f; z -= 20.0f) {
        SCOPED_TRACE("station at z = " + std::to_string(z));
        const Pose rest = rest_at(s, z, theta);
        // a 0.1 s ramp to the press, held 0.1 s; the window may move at the first step only
        s.place_probe({rest, 0.0});
        s.advance(kStep);
        const int serial = s.window_serial();
        double weakest = 1e9;
        for (int i = 2; i <= 200; ++i) {
            s.place_probe({rest, press * std::min(1.0, i * kStep / 0.1)});
            s.advance(kStep);
            if (i > 150) {
                const SessionView& v = s.view();
                ASSERT_TRUE(v.in_contact) << "step " << i;
                ASSERT_TRUE(v.over_model) << "step " << i;
                weakest = std::min(weakest, v.probe_force_N);
            }
        }
        EXPECT_EQ(s.window_serial(), serial) << "the window never moves under a pressed probe";
        EXPECT_NEAR(weakest, reference, kForceTolerance * reference);
        lift(s);
    }
    // 300 mm in steps of 20 mm, the window re-centred whenever the probe lands 20 mm or more
    // (Session::kZoneAlongMm) from its centre: about every other station
    EXPECT_GE(s.window_moves().moves, 6);
    EXPECT_LE(s.window_moves().moves, 16);
    EXPECT_TRUE(window_covers(s, -300.0f));
    EXPECT_EQ(s.window_moves().abandoned, 0) << "lock-step checks the lift where it decides";
}

// The window's mouse and keyboard slide the probe over the whole course, not only the home patch
// (haptics::exam_limb_surface): slid resting on the skin from the groin to the adductor canal,
// the window follows, and a press there (W) is felt as at home; T turns the probe longitudinal.
TEST(ExamWindow, TheMouseAndKeyboardReachTheCanalAndPressThere)
{
    const scene::LegModel home;
    auto mouse = std::make_shared<device::MouseKeyboardDevice>(device::SurfacePlacement{}, haptics::exam_limb_surface(home));
    SessionOptions o = following();
    o.device = mouse;
    Session s(o);
    const double dt = 1.0 / 60;
    int frames = 0;
    // the arrow key held: 0.4 of the patch a second (app/window_input.cpp)
    while (s.view().probe.position.z > -300.0f && frames < 6000) {
        mouse->feed({.du = 0.4 * dt});
        s.advance(dt);
        ++frames;
    }
    ASSERT_LE(s.view().probe.position.z, -300.0f) << "the probe stopped at z = " << s.view().probe.position.z;
    for (int i = 0; i < 30; ++i) s.advance(dt);  // resting: the window's last move lands
    EXPECT_TRUE(window_covers(s, s.view().probe.position.z));
    for (int i = 0; i < 30; ++i) {
        mouse->feed({.dpress_mm = 6.0 / 30});  // W held for half a second
        s.advance(dt);
    }
    for (int i = 0; i < 12; ++i) s.advance(dt);  // held 0.2 s
    const SessionView& v = s.view();
    EXPECT_TRUE(v.over_model);
    EXPECT_TRUE(v.in_contact);
    EXPECT_NEAR(v.probe_force_N, home_force(6.0), kForceTolerance * home_force(6.0));

    const glm::vec3 across = v.probe.axis_x();
    mouse->feed({.turn = true});
    s.advance(dt);
    const glm::vec3 along = s.view().probe.axis_x();
    EXPECT_LT(std::abs(glm::dot(across, along)), 0.01f) << "a quarter turn";
    EXPECT_GT(std::abs(along.z), 0.9f) << "the array along the limb (world z runs down it)";
}

// Real time: after await_device the view shows the probe where the device was just moved (the
// haptic loop read it), not where it was; lock-step and a stopped session return at once.
TEST(ExamWindow, AwaitDeviceLetsTheViewShowTheDevicesNewPose)
{
    const scene::LegModel leg;
    const Pose a = pressed_along_beam(leg.probe_rest_pose(0.5f, 0.5f), 2.0), b = pressed_along_beam(leg.probe_rest_pose(0.55f, 0.5f), 2.0);
    auto hand = std::make_shared<device::HeldDevice>(a, "moved hand");
    SessionOptions o;
    o.clock = Clock::real_time;
    o.device = hand;
    o.haptics.realtime_priority = false;
    Session s(o);
    for (Pose to : {b, a, b}) {
        hand->move_to(to);
        s.await_device(std::chrono::seconds(5));  // two ticks: a millisecond or two, or more on a loaded machine
        s.advance(1.0 / 60);
        EXPECT_LT(glm::distance(s.view().probe.position, to.position), 1e-3f);
    }
    s.stop();
    const auto start = std::chrono::steady_clock::now();
    s.await_device(std::chrono::seconds(5));
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1)) << "a stopped session's loop ticks no more: no wait";
}

// Lock-step with the window moving: the same script twice gives the same forces, bit for bit.
std::vector<double> scripted_walk()
{
    Session s(following());
    std::vector<double> forces;
    for (float z : {0.0f, -40.0f, -90.0f}) {
        const Pose rest = rest_at(s, z, home_theta() + 0.05f * z * kDeg);
        for (int i = 1; i <= 150; ++i) {
            s.place_probe({rest, 5.0 * std::min(1.0, i * kStep / 0.1)});
            s.advance(kStep);
            forces.push_back(s.view().probe_force_N);
        }
        lift(s);
        forces.push_back(s.view().probe_force_N);
    }
    EXPECT_GE(s.window_serial(), 2);
    forces.push_back(double(s.window_serial()));
    return forces;
}

TEST(ExamWindow, LockStepRunsWithMovesAreRepeatable)
{
    const std::vector<double> first = scripted_walk(), second = scripted_walk();
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << "sample " << i;
    EXPECT_GT(*std::max_element(first.begin(), first.end() - 1), 1.0) << "the script presses";
}

// A probe pressed and slid past the central zone keeps its window until it is lifted.
TEST(ExamWindow, APressedProbeKeepsItsWindowUntilLifted)
{
    Session s(following());
    const float theta = s.window().centre_theta();
    const float z0 = s.leg().limb_point({s.window().centre_t(), theta}).z;
    for (int i = 1; i <= 100; ++i) {
        s.place_probe({rest_at(s, z0, theta), 6.0 * i / 100.0});
        s.advance(kStep);
    }
    // 30 mm down the thigh at 100 mm/s, pressing
    for (int i = 1; i <= 300; ++i) {
        s.place_probe({rest_at(s, z0 - 0.1f * float(i), theta), 6.0});
        s.advance(kStep);
        ASSERT_GT(s.view().probe_force_N, 1.0) << "step " << i;
    }
    EXPECT_EQ(s.window_serial(), 0);
    EXPECT_TRUE(s.view().over_model) << "30 mm from the centre is still on the tissue grid";
    lift(s);
    EXPECT_EQ(s.window_serial(), 1) << "lifted 30 mm from the centre: re-centred";
    EXPECT_TRUE(window_covers(s, z0 - 30.0f));
}

TEST(ExamWindow, AProbeAwayFromTheLegOrAFixedWindowMovesNothing)
{
    {
        Session s(following());
        // 100 mm above the adductor canal: waved about, not put down
        s.place_probe({pressed_along_beam(rest_at(s, -300.0f, home_theta()), -100.0), 0.0});
        for (int i = 0; i < 20; ++i) s.advance(kStep);
        EXPECT_EQ(s.window_serial(), 0);
        EXPECT_FALSE(s.view().over_model);
        // pushed 6 mm into the leg there, where no tissue is simulated: it feels nothing, but it is
        // not lifted, so the window does not appear around it; lifted, it does
        const Pose canal = rest_at(s, -300.0f, home_theta());
        s.place_probe({canal, 6.0});
        for (int i = 0; i < 20; ++i) s.advance(kStep);
        EXPECT_EQ(s.view().probe_force_N, 0.0);
        EXPECT_EQ(s.window_serial(), 0);
        s.place_probe({canal, 0.0});
        s.advance(kStep);
        EXPECT_EQ(s.window_serial(), 1);
    }
    {
        Session s;  // the window stays where it starts unless asked to follow
        s.press_and_settle(rest_at(s, -300.0f, home_theta()), 6.0);
        EXPECT_EQ(s.window_serial(), 0);
        const SessionView& v = s.view();
        EXPECT_FALSE(v.over_model) << "the canal is off the home patch";
        EXPECT_FALSE(v.in_contact);
        EXPECT_EQ(v.probe_force_N, 0.0) << "no tissue is simulated under it";
    }
}

TEST(ExamWindow, MoveWindowPutsItWhereAsked)
{
    Session s;
    const scene::LimbCoordinates knee{s.leg().limb_t_at_z(-450.0f), 45.0f * kDeg};
    ASSERT_TRUE(s.move_window(knee));
    EXPECT_EQ(s.window_serial(), 1);
    scene::LegOptions o;
    o.patch_centre = knee;
    EXPECT_EQ(s.window().cells, scene::LegModel(o).patch().cells);
    EXPECT_FALSE(s.move_window(knee)) << "already there";
    EXPECT_EQ(s.window_serial(), 1);
    // the view follows at once: the new patch at rest
    const SessionView& v = s.view();
    ASSERT_EQ(v.patch->size(), s.leg().patch().rest.vertices.size());
    for (std::size_t k = 0; k < v.patch->size(); k += 97)
        EXPECT_LT(glm::length((*v.patch)[k].position - s.leg().patch().rest.vertices[k].position), 1e-3f);
}

// A large patient (SessionOptions::tissue_depth_scale): a column twice as deep compresses twice as
// far under the same force, so a press twice as deep pushes back as the fitted thigh's does: the
// columns alone would give the same force exactly; the deeper press also widens the flat face's
// footprint on the curved thigh, which adds up to a fifth.
TEST(ExamWindow, ADeeperTissuePushesBackAtTwiceThePressAsTheThighDoesAtOne)
{
    const double reference = home_force(5.0);
    SessionOptions o;
    o.tissue_depth_scale = 2.0;
    Session deep(o);
    const Pose centre = deep.leg().probe_rest_pose(0.5f, 0.5f);
    const SettleReport same_press = deep.press_and_settle(centre, 5.0);
    const SettleReport twice = deep.press_and_settle(centre, 10.0);
    ASSERT_TRUE(same_press.settled && twice.settled);
    EXPECT_LT(same_press.force_N, 0.7 * reference) << "softer to press through";
    EXPECT_NEAR(twice.force_N, reference, 0.2 * reference);
    EXPECT_GT(home_force(10.0), 2.0 * twice.force_N) << "the fitted thigh at 10 mm is far stiffer";
}

TEST(ExamWindow, TheDefaultDepthScaleLeavesTheFittedThighAsItIs)
{
    const Session s;
    const tissue::TissueModel shipped = load_simulation_model(scene::LegModel{});
    EXPECT_EQ(s.tissue_model().a, shipped.a);
    EXPECT_EQ(s.tissue_model().b, shipped.b);
    for (double bad : {0.0, -1.0, 10.0, std::nan("")}) {
        SessionOptions o;
        o.tissue_depth_scale = bad;
        try {
            Session refused(o);
            ADD_FAILURE() << "scale " << bad << " was taken";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("tissue_depth_scale"), std::string::npos) << e.what();
        }
    }
}

// Real time: the physics thread is stopped, swapped and started again while the haptic loop keeps
// ticking on its own thread. A hand presses at home, lifts, carries the probe to the adductor canal
// and hovers there until the window has followed, then presses; the press there is felt. Each stage
// waits for its outcome (bounded by a deadline far past any build's: a sanitizer's build on a
// loaded machine builds the window ten times slower), not for a fixed time: a hand that pressed
// before the window arrived would rightly keep the old one (APressedProbeKeepsItsWindowUntilLifted).
TEST(ExamWindow, RealTimeMovesWhileTheHapticLoopTicks)
{
    const scene::LegModel leg;
    const Pose home = leg.probe_rest_pose(0.5f, 0.5f);
    const Pose canal = leg.limb_rest_pose({leg.limb_t_at_z(-300.0f), home_theta()});
    auto hand = std::make_shared<device::HeldDevice>(pressed_along_beam(home, 5.0), "moved hand");
    SessionOptions o = following();
    o.clock = Clock::real_time;
    o.device = hand;
    o.haptics.realtime_priority = false;
    Session s(o);
    std::int64_t ticks_at_move = -1;
    // steps the session as a 60 Hz driver would until `done` holds; false at the deadline
    const auto until = [&](auto done) {
        const auto start = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - start < std::chrono::seconds(90)) {
            const int before = s.window_serial();
            s.advance(1.0 / 60);
            if (s.window_serial() != before && ticks_at_move < 0) ticks_at_move = s.haptic_loop()->ticks();
            if (done(s.view())) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(16));
        }
        return false;
    };
    const auto pressed = [](const SessionView& v) { return v.over_model && v.in_contact && v.haptic_force_N > 1.0; };
    ASSERT_TRUE(until(pressed)) << "the press at home is felt";
    EXPECT_EQ(s.window_serial(), 0) << "a pressed probe keeps its window";

    hand->move_to(pressed_along_beam(home, -5.0));
    ASSERT_TRUE(until([](const SessionView& v) { return !v.in_contact; })) << "the lifted probe leaves the skin";
    hand->move_to(pressed_along_beam(canal, -1.0));  // hovering 1 mm over the canal
    ASSERT_TRUE(until([&](const SessionView&) { return window_covers(s, -300.0f); })) << "the window follows the hovering probe";
    EXPECT_GE(s.window_serial(), 1);
    ASSERT_GE(ticks_at_move, 0);

    hand->move_to(pressed_along_beam(canal, 5.0));
    EXPECT_TRUE(until(pressed)) << "the press at the canal is felt";
    EXPECT_TRUE(window_covers(s, -300.0f));
    const std::int64_t ticks = s.haptic_loop()->ticks();
    EXPECT_TRUE(until([&](const SessionView&) { return s.haptic_loop()->ticks() > ticks; })) << "the haptic loop ticks on after the move";
    EXPECT_GT(s.haptic_loop()->ticks(), ticks_at_move);
    s.stop();
}

}  // namespace
}  // namespace echosim::session

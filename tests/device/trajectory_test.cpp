// The scripted driver's trajectory file (DESIGN.md §3) and the scripted device that plays it.
#include "device/trajectory.hpp"

#include <numbers>

#include <gtest/gtest.h>

#include "device/scripted_device.hpp"

namespace echosim::device {
namespace {

std::string expect_refused(const std::string& text)
{
    try {
        Trajectory::parse(text, "t.csv");
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return {};
}

TEST(Trajectory, TheScriptedDeviceReproducesItsCsvExactly)
{
    // awkward values: reading them back must give the very same doubles
    std::vector<TrajectoryRow> rows(3);
    rows[0] = {0.0, {1.0 / 3.0, -120.25, 1e-7}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()))};
    rows[1] = {0.0125, {0.1, 0.2, 0.3}, Eigen::Quaterniond(Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()))};
    rows[2] = {2.5, {-7.0, 8e3, 9.5}, Eigen::Quaterniond::Identity()};
    ScriptedDevice device(Trajectory::parse(format_trajectory(rows), "rows"), "rows");
    for (const TrajectoryRow& r : rows) {
        DeviceSample s;
        ASSERT_TRUE(device.read(r.t_s, s));
        EXPECT_EQ(s.control, Control::world);
        EXPECT_TRUE(s.connected);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(s.position[i], r.position[i]) << "row at " << r.t_s << " s";
        EXPECT_EQ(s.orientation.coeffs(), r.orientation.coeffs()) << "row at " << r.t_s << " s";
    }
}

TEST(Trajectory, InterpolatesBetweenRowsAndHoldsOutside)
{
    const Trajectory t = Trajectory::parse("t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n"
                                           "1, 0,0,0, 1,0,0,0\n"
                                           "3, 10,-20,4, 0.7071067811865476,0,0,0.7071067811865476\n",
                                           "t.csv");
    const TrajectoryRow mid = t.at(2.0);
    EXPECT_NEAR(mid.position.x(), 5.0, 1e-12);
    EXPECT_NEAR(mid.position.y(), -10.0, 1e-12);
    EXPECT_NEAR(mid.position.z(), 2.0, 1e-12);
    // halfway through a 90 degree turn about z: 45 degrees
    EXPECT_NEAR(Eigen::AngleAxisd(mid.orientation).angle(), 0.25 * std::numbers::pi, 1e-9);
    EXPECT_EQ(t.at(-5.0).position, Eigen::Vector3d::Zero());
    EXPECT_EQ(t.at(99.0).position, Eigen::Vector3d(10, -20, 4));
}

TEST(Trajectory, ALoopedScriptedDeviceStartsOverAtItsLastRow)
{
    // from x = 0 at 1 s to x = 10 at 3 s and back to 0 at 5 s: a 4 s loop
    const Trajectory t = Trajectory::parse("t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n"
                                           "1, 0,0,0, 1,0,0,0\n"
                                           "3, 10,0,0, 1,0,0,0\n"
                                           "5, 0,0,0, 1,0,0,0\n",
                                           "t.csv");
    ScriptedDevice looped(t, "loop", ScriptedDevice::Playback::loop), once(t, "once");
    DeviceSample s;
    for (double t_s : {2.0, 6.0, 10.0, 4002.0}) {
        ASSERT_TRUE(looped.read(t_s, s));
        EXPECT_NEAR(s.position.x(), 5.0, 1e-9) << "at " << t_s << " s";
    }
    looped.read(7.0, s);  // round two's far end
    EXPECT_NEAR(s.position.x(), 10.0, 1e-9);
    looped.read(0.5, s);  // before the first row it holds, looped or not
    EXPECT_EQ(s.position.x(), 0.0);
    once.read(7.0, s);
    EXPECT_EQ(s.position.x(), 0.0);
    std::vector<DeviceEvent> events;
    looped.events(events);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_NE(events[0].message.find("looped"), std::string::npos) << events[0].message;
}

TEST(Trajectory, RefusesBadFilesNamingLineAndField)
{
    const std::string h = "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n";
    EXPECT_NE(expect_refused("t,x,y,z\n0,0,0,0\n").find("t.csv:1: the header must be"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,2,3,1,0,0\n").find("t.csv:2: qz is missing"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,nan,3,1,0,0,0\n").find("t.csv:2: y_mm 'nan' is not a finite number"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,1e999,3,1,0,0,0\n").find("y_mm"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,2,1e39,1,0,0,0\n").find("t.csv:2: z_mm '1e39' is more than a kilometre"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,2,3,2,0,0,0\n").find("t.csv:2: qw,qx,qy,qz is not a unit quaternion"), std::string::npos);
    EXPECT_NE(expect_refused(h + "1,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n").find("t.csv:3: t_s 1.000000 does not increase"), std::string::npos);
    EXPECT_NE(expect_refused(h + "0,1,2,3,1,0,0,0,9\n").find("more than 8 fields"), std::string::npos);
    EXPECT_NE(expect_refused(h).find("no rows"), std::string::npos);
    EXPECT_NE(expect_refused("").find("empty"), std::string::npos);
}

}  // namespace
}  // namespace echosim::device

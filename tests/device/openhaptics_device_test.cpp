// The Touch/Phantom driver (device/openhaptics_device.cpp) against a fake libHD (fake_hd/fake_hd.cpp),
// a shared library built by the tests and loaded through the driver's own dlopen/dlsym loader:
// opening and its errors, the force cut and sent in the arm's frame inside a servo frame, the pose
// about the workspace's centre, buttons, faults and their recovery, and the stop's order.
#include "device/openhaptics_device.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "device/fake_hd/fake_hd_control.hpp"

namespace echosim::device {
namespace {

using namespace hd;

class OpenHapticsDeviceTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        load_ = load_hd_library({ECHOSIM_FAKE_HD_PATH});
        ASSERT_TRUE(load_.api) << load_.error;
    }
    Eigen::Vector3d sent() const
    {
        double f[3];
        fake_.sent_force(f);
        return {f[0], f[1], f[2]};
    }
    std::string calls() const { return fake_.calls(); }

    test::FakeHd fake_{ECHOSIM_FAKE_HD_PATH};
    HdLoad load_;
};

TEST_F(OpenHapticsDeviceTest, TheLoaderBindsEveryFunctionOrSaysWhatIsMissing)
{
    EXPECT_NE(load_.api->path.find("fake_hd"), std::string::npos) << load_.api->path;
    EXPECT_NE(load_.api->hdScheduleAsynchronous, nullptr);

    const HdLoad none = load_hd_library({"/nonexistent/libHD.so"});
    EXPECT_FALSE(none.api);
    EXPECT_NE(none.error.find("/nonexistent/libHD.so"), std::string::npos) << none.error;
    // a library that opens but is not OpenHaptics' (zlib is linked into every echosim)
    const HdLoad wrong = load_hd_library({"libz.so.1"});
    EXPECT_FALSE(wrong.api);
    EXPECT_NE(wrong.error.find("lacks hdInitDevice"), std::string::npos) << wrong.error;
    // the first that works wins
    const HdLoad second = load_hd_library({"/nonexistent/libHD.so", ECHOSIM_FAKE_HD_PATH});
    EXPECT_TRUE(second.api) << second.error;
}

TEST_F(OpenHapticsDeviceTest, AnArmThatDoesNotAnswerIsRefusedWithTheHdErrorAndNothingLeftRunning)
{
    fake_.fail_init(HD_COMM_ERROR, 5);
    try {
        OpenHapticsDevice arm(load_.api);
        FAIL() << "opened an arm that does not answer";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("hdInitDevice(HD_DEFAULT_DEVICE): HD_COMM_ERROR (0x0302, internal 5): Communication error"), std::string::npos)
            << what;
        EXPECT_NE(what.find("plugged in"), std::string::npos) << what;
    }
    EXPECT_EQ(fake_.state("scheduler"), 0);
    EXPECT_EQ(fake_.state("force_output"), 0);
    EXPECT_EQ(calls(), "hdInitDevice(HD_DEFAULT_DEVICE)");

    // an arm that says it has no force limit is refused too, and disabled again
    fake_.reset();
    const double box[6] = {-80, -60, -35, 80, 60, 35};
    fake_.set_arm(box, 0.0, 0.0, 1.26, 0.0035);
    EXPECT_THROW(OpenHapticsDevice{load_.api}, std::runtime_error);
    EXPECT_EQ(fake_.state("device_disabled"), 1);
    EXPECT_EQ(fake_.state("scheduler"), 0);
}

TEST_F(OpenHapticsDeviceTest, OpensTheArmWithItsOwnLimitsAndStartsItsServo)
{
    const double box[6] = {-80, -50, -30, 80, 70, 40};  // not centred on the arm's origin
    fake_.set_arm(box, 3.3, 0.88, 1.26, 0.0035);
    OpenHapticsDevice arm(load_.api);
    const Capabilities& c = arm.capabilities();
    EXPECT_EQ(c.name, "3D Systems Touch");
    EXPECT_EQ(c.control, Control::workspace);
    EXPECT_DOUBLE_EQ(c.max_force_N, 0.88);  // the continuous force, not the 3.3 N peak
    EXPECT_DOUBLE_EQ(c.max_stiffness_N_per_mm, 1.26);
    EXPECT_DOUBLE_EQ(c.max_damping_N_s_per_mm, 0.0035);
    EXPECT_LT((c.workspace_mm - Eigen::Vector3d(160, 120, 70)).norm(), 1e-12);
    EXPECT_EQ(c.degrees_of_freedom, 6);
    EXPECT_NE(c.address.find("FAKE-0001"), std::string::npos) << c.address;
    EXPECT_EQ(fake_.state("force_output"), 1);
    EXPECT_EQ(fake_.state("scheduler"), 1);
    EXPECT_EQ(fake_.state("scheduled"), 1);

    std::vector<DeviceEvent> events;
    arm.events(events);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, DeviceEvent::Kind::connected);
}

TEST_F(OpenHapticsDeviceTest, AnArmWithoutAContinuousFigureIsHeldToItsPeak)
{
    const double box[6] = {-80, -60, -35, 80, 60, 35};
    fake_.set_arm(box, 3.3, 0.0, 1.26, 0.0035);  // HD_NOMINAL_MAX_CONTINUOUS_FORCE answers HD_INVALID_ENUM
    const OpenHapticsDevice arm(load_.api);
    EXPECT_DOUBLE_EQ(arm.capabilities().max_force_N, 3.3);
}

TEST_F(OpenHapticsDeviceTest, MapsTheHandlesTransformAboutTheWorkspaceCentreAndReadsItsButtons)
{
    const double box[6] = {-80, -50, -30, 80, 70, 40};  // centre (0, 10, 5)
    fake_.set_arm(box, 3.3, 0.88, 1.26, 0.0035);
    OpenHapticsDevice arm(load_.api);
    DeviceSample s;
    EXPECT_FALSE(arm.read(0.0, s)) << "connected before the servo's first frame";

    // the stylus turned 90 degrees about y, at (10, -20, 35) mm: column-major, as HD_CURRENT_TRANSFORM
    const Eigen::Matrix3d r = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    double m[16] = {};
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) m[col * 4 + row] = r(row, col);
    m[12] = 10, m[13] = -20, m[14] = 35, m[15] = 1;
    fake_.set_pose(m, 2);  // HD_DEVICE_BUTTON_2
    ASSERT_EQ(fake_.servo(1), 1);
    ASSERT_TRUE(arm.read(0.001, s));
    EXPECT_EQ(s.control, Control::workspace);
    EXPECT_LT((s.position - Eigen::Vector3d(10, -30, 30)).norm(), 1e-12);
    EXPECT_LT(s.orientation.angularDistance(Eigen::Quaterniond(r)), 1e-9);
    EXPECT_EQ(s.buttons, 2u);
    const std::uint64_t first = s.sequence;
    fake_.servo(1);
    arm.read(0.002, s);
    EXPECT_EQ(s.sequence, first + 1);
}

TEST_F(OpenHapticsDeviceTest, CutsTheForceToTheArmsLimitAndSendsItInItsFrameInsideAServoFrame)
{
    OpenHapticsDevice arm(load_.api);  // the fake's Touch: 0.88 N continuous
    arm.write_force(Eigen::Vector3d(0.3, -0.4, 0.0));  // within: as is, the device's axes and newtons
    fake_.servo(1);
    EXPECT_LT((sent() - Eigen::Vector3d(0.3, -0.4, 0.0)).norm(), 1e-12);

    arm.write_force(Eigen::Vector3d(0.0, 3.0, 4.0));  // 5 N: cut to 0.88 N along the same direction
    fake_.servo(1);
    EXPECT_LT((sent() - Eigen::Vector3d(0.0, 0.6, 0.8) * 0.88).norm(), 1e-12);

    arm.write_force(Eigen::Vector3d(std::nan(""), 0.2, 0.0));  // nothing sent for a NaN
    fake_.servo(1);
    EXPECT_EQ(sent(), Eigen::Vector3d::Zero());
    EXPECT_EQ(fake_.state("sets_outside_frame"), 0);
    EXPECT_EQ(fake_.state("frames_open"), 0);

    // a force the loop stops renewing is dropped after kForceHoldS
    arm.write_force(Eigen::Vector3d(0.0, 0.5, 0.0));
    fake_.servo(1);
    EXPECT_DOUBLE_EQ(sent().y(), 0.5);
    std::this_thread::sleep_for(std::chrono::duration<double>(kForceHoldS * 1.5));
    fake_.servo(1);
    EXPECT_EQ(sent(), Eigen::Vector3d::Zero());
}

TEST_F(OpenHapticsDeviceTest, AFaultIsSaidWithTheHdErrorTheArmGoesLimpAndComesBack)
{
    OpenHapticsDevice arm(load_.api);
    std::vector<DeviceEvent> events;
    arm.events(events);
    events.clear();
    DeviceSample s;
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    ASSERT_TRUE(arm.read(0.0, s));

    fake_.set_fault(HD_COMM_ERROR, 12);  // unplugged
    fake_.servo(1);
    EXPECT_FALSE(arm.read(0.001, s));
    // no force is sent to an arm that failed its last frame, whatever the loop asks
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    std::string log = calls();
    EXPECT_EQ(log.substr(log.rfind("force=")), "force=0,0,0") << log;
    arm.events(events);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, DeviceEvent::Kind::disconnected);
    EXPECT_NE(events[0].message.find("HD_COMM_ERROR (0x0302, internal 12)"), std::string::npos) << events[0].message;
    fake_.servo(3);
    events.clear();
    arm.events(events);
    EXPECT_TRUE(events.empty()) << "said once, not once a frame";

    fake_.set_fault(HD_SUCCESS, 0);  // back: its first clean frame sends nothing yet, the next the loop's force
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    EXPECT_TRUE(arm.read(0.002, s));
    EXPECT_EQ(sent(), Eigen::Vector3d::Zero());
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    EXPECT_DOUBLE_EQ(sent().y(), 0.5);
    arm.events(events);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, DeviceEvent::Kind::connected);

    // a force error (the arm's own safety cut the force) is a note, and the arm stays connected
    fake_.queue_error(HD_EXCEEDED_MAX_VELOCITY);
    fake_.servo(1);
    EXPECT_TRUE(arm.read(0.003, s));
    events.clear();
    arm.events(events);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, DeviceEvent::Kind::note);
    EXPECT_NE(events[0].message.find("HD_EXCEEDED_MAX_VELOCITY (0x0203): the arm cut its force itself"), std::string::npos)
        << events[0].message;

    // a force error queued before a fault in the same frame does not hide the fault
    fake_.queue_error(HD_EXCEEDED_MAX_VELOCITY);
    fake_.queue_error(HD_COMM_ERROR);
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    EXPECT_FALSE(arm.read(0.004, s)) << "a frame with a communication error was taken as the handle's";
    arm.write_force(Eigen::Vector3d(0, 0.5, 0));
    fake_.servo(1);
    EXPECT_TRUE(arm.read(0.005, s));
    EXPECT_EQ(sent(), Eigen::Vector3d::Zero()) << "a force was sent on the frame after a fault";
}

TEST_F(OpenHapticsDeviceTest, StoppingSendsZeroForceFirstThenStopsTheServoAndDisablesTheArm)
{
    {
        OpenHapticsDevice arm(load_.api);
        arm.write_force(Eigen::Vector3d(0, 0.5, 0));
        fake_.servo(1);
        ASSERT_DOUBLE_EQ(sent().y(), 0.5);
        // a zero command (a signal's stop) takes effect at the next servo frame
        arm.write_force(Eigen::Vector3d::Zero());
        fake_.servo(1);
        EXPECT_EQ(sent(), Eigen::Vector3d::Zero());
        arm.write_force(Eigen::Vector3d(0, 0.5, 0));
        fake_.servo(1);
        ASSERT_DOUBLE_EQ(sent().y(), 0.5);
    }
    EXPECT_EQ(sent(), Eigen::Vector3d::Zero());
    const std::string log = calls();
    const std::size_t zero = log.rfind("hdScheduleSynchronous force=0,0,0");
    ASSERT_NE(zero, std::string::npos) << log;
    EXPECT_NE(log.find("hdStopScheduler hdUnschedule hdDisable(0x4000) hdDisableDevice(1)", zero), std::string::npos) << log;
    EXPECT_EQ(fake_.state("scheduler"), 0);
    EXPECT_EQ(fake_.state("force_output"), 0);
    EXPECT_EQ(fake_.state("device_disabled"), 1);
    EXPECT_EQ(fake_.state("scheduled"), 0);
}

TEST_F(OpenHapticsDeviceTest, TheDeviceListSaysWhatIsMissingOrWhatAnswers)
{
    const OpenHapticsProbe missing = probe_openhaptics(HdLoad{nullptr, "libHD.so: cannot open shared object file"});
    EXPECT_FALSE(missing.library_found);
    EXPECT_FALSE(missing.available);
    EXPECT_NE(missing.status.find("not found"), std::string::npos) << missing.status;
    EXPECT_NE(missing.status.find(kInstallHint), std::string::npos) << missing.status;
    EXPECT_DOUBLE_EQ(missing.capabilities.max_force_N, 0.88);  // the Touch's figures from device/README.md

    fake_.fail_init(HD_DEVICE_FAULT, 0);
    const OpenHapticsProbe silent = probe_openhaptics(load_);
    EXPECT_TRUE(silent.library_found);
    EXPECT_FALSE(silent.available);
    EXPECT_NE(silent.status.find("HD_DEVICE_FAULT (0x0300): Device fault"), std::string::npos) << silent.status;

    fake_.reset();
    const OpenHapticsProbe ready = probe_openhaptics(load_);
    EXPECT_TRUE(ready.available) << ready.status;
    EXPECT_EQ(ready.capabilities.name, "3D Systems Touch");
    EXPECT_EQ(fake_.state("device_disabled"), 1);
    EXPECT_EQ(fake_.state("scheduler"), 0);  // asked, not started
    EXPECT_EQ(fake_.state("force_output"), 0);
}

}  // namespace
}  // namespace echosim::device

// The window's mouse and keyboard as a device: what the window thread feeds is what the haptic
// thread reads, within the patch, the tilt and the press limits.
#include "device/mouse_keyboard_device.hpp"

#include <numbers>

#include <gtest/gtest.h>

namespace echosim::device {
namespace {

TEST(MouseKeyboardDevice, TheHapticSideReadsWhatTheWindowFed)
{
    MouseKeyboardDevice d;
    DeviceSample s;
    ASSERT_TRUE(d.read(0.0, s));
    EXPECT_EQ(s.surface.u, 0.5);
    EXPECT_EQ(s.surface.press_mm, 0.0);

    d.feed({.du = 0.1, .dv = -0.2, .dfan_rad = 0.1, .dpress_mm = 3.0});
    d.feed({.drock_rad = -0.05, .dpress_mm = 1.5});
    ASSERT_TRUE(d.read(0.1, s));
    EXPECT_EQ(s.control, Control::surface);
    EXPECT_DOUBLE_EQ(s.surface.u, 0.6);
    EXPECT_DOUBLE_EQ(s.surface.v, 0.3);
    EXPECT_DOUBLE_EQ(s.surface.fan_rad, 0.1);
    EXPECT_DOUBLE_EQ(s.surface.rock_rad, -0.05);
    EXPECT_DOUBLE_EQ(s.surface.press_mm, 4.5);
    EXPECT_EQ(s.sequence, 2u);
}

TEST(MouseKeyboardDevice, StaysWithinThePatchTheTiltAndThePress)
{
    MouseKeyboardDevice d;
    d.feed({.du = 5.0, .dv = -5.0, .dfan_rad = 2.0, .drock_rad = -2.0, .dpress_mm = 100.0});
    DeviceSample s;
    d.read(0.0, s);
    EXPECT_EQ(s.surface.u, 1.0);
    EXPECT_EQ(s.surface.v, 0.0);
    EXPECT_EQ(s.surface.fan_rad, SurfacePlacement::kMaxTiltRad);
    EXPECT_EQ(s.surface.rock_rad, -SurfacePlacement::kMaxTiltRad);
    EXPECT_EQ(s.surface.press_mm, SurfacePlacement::kMaxPressMm);
    d.feed({.press_mm = 2.0, .level = true});  // an absolute press wins; level undoes the tilt
    d.read(0.0, s);
    EXPECT_EQ(s.surface.press_mm, 2.0);
    EXPECT_EQ(s.surface.fan_rad, 0.0);
    EXPECT_EQ(s.surface.rock_rad, 0.0);
    d.feed({.dpress_mm = -10.0});
    d.read(0.0, s);
    EXPECT_EQ(s.surface.press_mm, 0.0);
}

// Limits wider than the patch (the whole course: haptics::exam_limb_surface) let the slide go past
// it and still stop at their ends; T turns the probe between transverse and longitudinal, and a
// twist (a SpaceMouse cap's) stays between the two.
TEST(MouseKeyboardDevice, SlidesWithinItsLimitsAndTurnsLongitudinal)
{
    MouseKeyboardDevice d({}, {-0.5, 6.0, -2.0, 3.0});
    DeviceSample s;
    d.feed({.du = 4.0, .dv = -2.0});
    d.read(0.0, s);
    EXPECT_DOUBLE_EQ(s.surface.u, 4.5);
    EXPECT_DOUBLE_EQ(s.surface.v, -1.5);
    d.feed({.du = 10.0, .dv = 10.0});
    d.read(0.0, s);
    EXPECT_EQ(s.surface.u, 6.0);
    EXPECT_EQ(s.surface.v, 3.0);

    EXPECT_EQ(s.surface.twist_rad, 0.0);
    d.feed({.turn = true});
    d.read(0.0, s);
    EXPECT_DOUBLE_EQ(s.surface.twist_rad, std::numbers::pi / 2);
    d.feed({.turn = true});
    d.read(0.0, s);
    EXPECT_EQ(s.surface.twist_rad, 0.0);
    d.feed({.dtwist_rad = 0.3});
    d.feed({.dtwist_rad = 5.0});
    d.read(0.0, s);
    EXPECT_DOUBLE_EQ(s.surface.twist_rad, std::numbers::pi / 2);
    d.feed({.dtwist_rad = -0.5});
    d.feed({.turn = true});  // from part way: back to transverse
    d.read(0.0, s);
    EXPECT_EQ(s.surface.twist_rad, 0.0);
    d.feed({.dtwist_rad = -1.0});
    d.read(0.0, s);
    EXPECT_EQ(s.surface.twist_rad, 0.0);
}

}  // namespace
}  // namespace echosim::device

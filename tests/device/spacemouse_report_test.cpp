// The SpaceMouse's reports as recorded bytes of both forms, and what its cap does to the placement.
// Expected values are worked out by hand from the bytes and the mapping's constants.
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "device/spacemouse_report.hpp"

namespace echosim::device {
namespace {

using Bytes = std::vector<std::uint8_t>;

SpaceMouseReport parse(SpaceMouseParser& p, const Bytes& b)
{
    return p.parse(std::span<const std::uint8_t>(b.data(), b.size()));
}

bool same(const SpaceMouseState& a, const SpaceMouseState& b)
{
    return a.tx == b.tx && a.ty == b.ty && a.tz == b.tz && a.rx == b.rx && a.ry == b.ry && a.rz == b.rz && a.buttons == b.buttons;
}

void expect_state(const SpaceMouseState& s, std::array<int, 6> axes, std::uint32_t buttons)
{
    EXPECT_EQ(s.tx, axes[0]);
    EXPECT_EQ(s.ty, axes[1]);
    EXPECT_EQ(s.tz, axes[2]);
    EXPECT_EQ(s.rx, axes[3]);
    EXPECT_EQ(s.ry, axes[4]);
    EXPECT_EQ(s.rz, axes[5]);
    EXPECT_EQ(s.buttons, buttons);
}

TEST(SpaceMouseReport, SeparateReportsOfTheOlderDevices)
{
    SpaceMouseParser p;
    // 0x015e = 350, 0xfea2 = -350
    EXPECT_EQ(parse(p, {0x01, 0x5e, 0x01, 0xa2, 0xfe, 0x00, 0x00}), SpaceMouseReport::translation);
    expect_state(p.state(), {350, -350, 0, 0, 0, 0}, 0);
    // 0x0028 = 40, 0xffd8 = -40, 0x0100 = 256
    EXPECT_EQ(parse(p, {0x02, 0x28, 0x00, 0xd8, 0xff, 0x00, 0x01}), SpaceMouseReport::rotation);
    expect_state(p.state(), {350, -350, 0, 40, -40, 256}, 0);
    // left button, then right, then both
    EXPECT_EQ(parse(p, {0x03, 0x01}), SpaceMouseReport::buttons);
    EXPECT_EQ(p.state().buttons, 1u);
    EXPECT_EQ(parse(p, {0x03, 0x02, 0x00}), SpaceMouseReport::buttons);
    EXPECT_EQ(p.state().buttons, 2u);
    EXPECT_EQ(parse(p, {0x03, 0x03}), SpaceMouseReport::buttons);
    EXPECT_EQ(p.state().buttons, 3u);
    // a Pro's wider mask, little-endian: button 0 and button 31; a fifth byte has no bit to go to
    EXPECT_EQ(parse(p, {0x03, 0x01, 0x00, 0x00, 0x80, 0xff}), SpaceMouseReport::buttons);
    EXPECT_EQ(p.state().buttons, 0x80000001u);
    // the axes did not move
    expect_state(p.state(), {350, -350, 0, 40, -40, 256}, 0x80000001u);
    EXPECT_EQ(p.unknown_reports(), 0u);
    EXPECT_EQ(p.truncated_reports(), 0u);
}

TEST(SpaceMouseReport, SingleMotionReportOfTheNewerDevices)
{
    SpaceMouseParser p;
    // tx 10, ty -10, tz 300 (0x012c), rx -32768, ry 32767, rz 1
    EXPECT_EQ(parse(p, {0x01, 0x0a, 0x00, 0xf6, 0xff, 0x2c, 0x01, 0x00, 0x80, 0xff, 0x7f, 0x01, 0x00}), SpaceMouseReport::motion);
    expect_state(p.state(), {10, -10, 300, -32768, 32767, 1}, 0);
    // a longer id-1 report is still both (padding after the rotation is ignored)
    EXPECT_EQ(parse(p, {0x01, 0x01, 0x00, 0x02, 0x00, 0x03, 0x00, 0x04, 0x00, 0x05, 0x00, 0x06, 0x00, 0xee, 0xee}),
              SpaceMouseReport::motion);
    expect_state(p.state(), {1, 2, 3, 4, 5, 6}, 0);
    // 10 bytes: the translation is whole, the rotation is not: the rotation keeps its values
    EXPECT_EQ(parse(p, {0x01, 0x64, 0x00, 0x9c, 0xff, 0x00, 0x00, 0x99, 0x99, 0x99}), SpaceMouseReport::translation);
    expect_state(p.state(), {100, -100, 0, 4, 5, 6}, 0);
}

TEST(SpaceMouseReport, TruncatedAndUnknownLeaveTheStateAlone)
{
    SpaceMouseParser p;
    parse(p, {0x01, 0x5e, 0x01, 0xa2, 0xfe, 0x2c, 0x01, 0x28, 0x00, 0xd8, 0xff, 0x00, 0x01});
    parse(p, {0x03, 0x05});
    const std::array<int, 6> before = {350, -350, 300, 40, -40, 256};
    expect_state(p.state(), before, 5);

    EXPECT_EQ(parse(p, {}), SpaceMouseReport::truncated);
    EXPECT_EQ(parse(p, {0x01, 0x00, 0x00, 0x00, 0x00}), SpaceMouseReport::truncated);        // id 1, 5 bytes
    EXPECT_EQ(parse(p, {0x01, 0x00, 0x00, 0x00, 0x00, 0x00}), SpaceMouseReport::truncated);  // id 1, 6 bytes
    EXPECT_EQ(parse(p, {0x02, 0x00, 0x00, 0x00, 0x00, 0x00}), SpaceMouseReport::truncated);  // id 2, 6 bytes
    EXPECT_EQ(parse(p, {0x03}), SpaceMouseReport::truncated);                                // id 3, no mask
    EXPECT_EQ(p.truncated_reports(), 5u);
    expect_state(p.state(), before, 5);

    EXPECT_EQ(parse(p, {0x17, 0x64}), SpaceMouseReport::unknown);  // a wireless model's battery level
    EXPECT_EQ(parse(p, {0x00}), SpaceMouseReport::unknown);
    EXPECT_EQ(parse(p, {0x04, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06}), SpaceMouseReport::unknown);
    EXPECT_EQ(p.unknown_reports(), 3u);
    expect_state(p.state(), before, 5);

    p.reset();
    expect_state(p.state(), {0, 0, 0, 0, 0, 0}, 0);
}

// Any byte string: the kind follows from id and length alone, and a report that is not used does
// not touch the state.
TEST(SpaceMouseReport, RandomBytesNeverCrashAndFollowTheRules)
{
    std::mt19937 rng(20240611);
    std::uniform_int_distribution<int> length(0, 70), byte(0, 255), small_id(0, 5), coin(0, 1);
    SpaceMouseParser p;
    std::uint64_t truncated = 0, unknown = 0;
    for (int i = 0; i < 200000; ++i) {
        Bytes b(std::size_t(length(rng)));
        for (std::uint8_t& x : b) x = std::uint8_t(byte(rng));
        if (!b.empty() && coin(rng) == 1) b[0] = std::uint8_t(small_id(rng));  // mostly ids we read
        const SpaceMouseState before = p.state();

        SpaceMouseReport expected = SpaceMouseReport::unknown;
        if (b.empty()) expected = SpaceMouseReport::truncated;
        else if (b[0] == 1) expected = b.size() < 7 ? SpaceMouseReport::truncated : b.size() < 13 ? SpaceMouseReport::translation : SpaceMouseReport::motion;
        else if (b[0] == 2) expected = b.size() < 7 ? SpaceMouseReport::truncated : SpaceMouseReport::rotation;
        else if (b[0] == 3) expected = b.size() < 2 ? SpaceMouseReport::truncated : SpaceMouseReport::buttons;

        const SpaceMouseReport got = parse(p, b);
        ASSERT_EQ(got, expected) << "report " << i << " of " << b.size() << " bytes";
        if (got == SpaceMouseReport::truncated) ++truncated;
        if (got == SpaceMouseReport::unknown) ++unknown;
        if (got == SpaceMouseReport::truncated || got == SpaceMouseReport::unknown) {
            ASSERT_TRUE(same(before, p.state())) << "report " << i;
        }
        if (got == SpaceMouseReport::rotation) {
            ASSERT_EQ(p.state().rx, std::int16_t(b[1] | b[2] << 8));
            ASSERT_EQ(p.state().tx, before.tx);
        }
    }
    EXPECT_EQ(p.truncated_reports(), truncated);
    EXPECT_EQ(p.unknown_reports(), unknown);
    EXPECT_GT(truncated, 0u);
    EXPECT_GT(unknown, 0u);
}

TEST(SpaceMouseMapping, DeadZoneThenLinearFromItsEdge)
{
    const SpaceMouseMapping m;  // dead zone 40, full scale 350: 310 counts of travel
    EXPECT_EQ(deflection(0, m), 0.0);
    EXPECT_EQ(deflection(25, m), 0.0);
    EXPECT_EQ(deflection(40, m), 0.0);
    EXPECT_EQ(deflection(-40, m), 0.0);
    // just outside: one count of travel, not a jump to 40/350
    EXPECT_DOUBLE_EQ(deflection(41, m), 1.0 / 310.0);
    EXPECT_DOUBLE_EQ(deflection(-41, m), -1.0 / 310.0);
    EXPECT_LT(deflection(41, m), 0.01);
    EXPECT_DOUBLE_EQ(deflection(195, m), 0.5);
    EXPECT_DOUBLE_EQ(deflection(350, m), 1.0);
    EXPECT_DOUBLE_EQ(deflection(-350, m), -1.0);
    EXPECT_DOUBLE_EQ(deflection(500, m), 1.0);  // past full scale: held at full
    EXPECT_DOUBLE_EQ(deflection(-32768, m), -1.0);

    // no step anywhere: neighbouring counts differ by one count's worth at most
    for (int c = -400; c < 400; ++c)
        ASSERT_LE(std::abs(deflection(std::int16_t(c + 1), m) - deflection(std::int16_t(c), m)), 1.0 / 310.0 + 1e-12) << c;

    SpaceMouseMapping narrow;
    narrow.dead_zone = 0;
    EXPECT_DOUBLE_EQ(deflection(35, narrow), 0.1);
}

TEST(SpaceMouseMapping, RatesAtFullDeflection)
{
    const SpaceMouseMapping m;
    SpaceMouseState s;
    s.tx = 350;   // around the thigh
    s.ty = -350;  // along it, backwards
    s.rx = 195;   // half way: fan at 15 degrees/s
    s.ry = -350;  // rock at -30 degrees/s
    s.rz = 350;   // twist: a quarter turn a second
    const SpaceMouseCommand c = command_of(s, m);
    EXPECT_DOUBLE_EQ(c.dtwist_rad_per_s, 90.0 * 3.14159265358979323846 / 180.0);
    EXPECT_DOUBLE_EQ(c.dv_per_s, 0.25);
    EXPECT_DOUBLE_EQ(c.du_per_s, -0.25);
    EXPECT_DOUBLE_EQ(c.dfan_rad_per_s, 15.0 * 3.14159265358979323846 / 180.0);
    EXPECT_DOUBLE_EQ(c.drock_rad_per_s, -30.0 * 3.14159265358979323846 / 180.0);
    EXPECT_EQ(c.press_mm, 0.0);
    EXPECT_FALSE(c.level);

    SpaceMouseMapping twice = m;
    twice.sensitivity = 2.0;
    EXPECT_DOUBLE_EQ(command_of(s, twice).dv_per_s, 0.5);
}

TEST(SpaceMouseMapping, PressFollowsThePushAndLiftsOnRelease)
{
    const SpaceMouseMapping m;
    SpaceMouseState s;
    s.tz = 350;  // all the way in
    EXPECT_DOUBLE_EQ(command_of(s, m).press_mm, 20.0);
    s.tz = 195;
    EXPECT_DOUBLE_EQ(command_of(s, m).press_mm, 10.0);
    s.tz = 41;
    EXPECT_DOUBLE_EQ(command_of(s, m).press_mm, 20.0 / 310.0);
    s.tz = 30;  // resting on the cap, inside the dead zone
    EXPECT_EQ(command_of(s, m).press_mm, 0.0);
    s.tz = -350;  // pulled up: lifted, not less than lifted
    EXPECT_EQ(command_of(s, m).press_mm, 0.0);

    // a position, not a rate: however long it is held, the press is where the cap is
    SurfacePlacement p;
    s.tz = 195;
    p = advanced(p, s, m, 0.5);
    EXPECT_DOUBLE_EQ(p.press_mm, 10.0);
    p = advanced(p, s, m, 3.0);
    EXPECT_DOUBLE_EQ(p.press_mm, 10.0);
    s.tz = 0;  // let go
    p = advanced(p, s, m, 0.001);
    EXPECT_EQ(p.press_mm, 0.0);

    // harder than the probe may go: held at SurfacePlacement's limit
    SpaceMouseMapping hard = m;
    hard.sensitivity = 2.0;
    s.tz = 350;
    EXPECT_DOUBLE_EQ(advanced(p, s, hard, 0.01).press_mm, SurfacePlacement::kMaxPressMm);
}

TEST(SpaceMouseMapping, AdvancesTheSurfacePlacementClamped)
{
    const SpaceMouseMapping m;
    SurfacePlacement p;  // the patch centre, upright, not pressed
    SpaceMouseState s;
    s.tx = 350;  // v at 0.25/s
    p = advanced(p, s, m, 0.4);
    EXPECT_DOUBLE_EQ(p.v, 0.6);
    EXPECT_DOUBLE_EQ(p.u, 0.5);
    p = advanced(p, s, m, 10.0);  // off the patch's edge: held on it
    EXPECT_EQ(p.v, 1.0);

    s = {};
    s.rx = 350;  // fan at 30 degrees/s for 0.5 s
    p = advanced(p, s, m, 0.5);
    EXPECT_DOUBLE_EQ(p.fan_rad, 15.0 * 3.14159265358979323846 / 180.0);
    p = advanced(p, s, m, 5.0);  // 165 degrees asked: held at the tilt limit
    EXPECT_DOUBLE_EQ(p.fan_rad, SurfacePlacement::kMaxTiltRad);

    s = {};
    s.ry = -350;
    p = advanced(p, s, m, 0.2);
    EXPECT_DOUBLE_EQ(p.rock_rad, -6.0 * 3.14159265358979323846 / 180.0);

    // button 0 levels the probe, whatever the cap is doing
    s.buttons = 1;
    p = advanced(p, s, m, 0.2);
    EXPECT_EQ(p.fan_rad, 0.0);
    EXPECT_EQ(p.rock_rad, 0.0);
    EXPECT_EQ(p.v, 1.0);
    // another button does not
    s.buttons = 2;
    s.ry = 350;
    p = advanced(p, s, m, 0.2);
    EXPECT_DOUBLE_EQ(p.rock_rad, 6.0 * 3.14159265358979323846 / 180.0);
}

}  // namespace
}  // namespace echosim::device

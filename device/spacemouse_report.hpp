// A 3Dconnexion SpaceMouse's HID input reports, and what its cap does to the probe over the skin.
// Pure: no I/O, no threads, no allocation; the driver (device/spacemouse_device.hpp) feeds it the bytes
// hid_read gives it, report id first.
//
// Two report forms exist in the family, and one driver meets both:
//   - older devices (SpaceNavigator, SpaceMouse Pro, ...) send three 7-byte reports: id 1 translation,
//     id 2 rotation (3 x int16 each), id 3 the buttons (a little-endian bit mask after the id);
//   - newer ones (SpaceMouse Wireless, Pro Wireless, Compact on newer firmware) send one 13-byte id 1
//     report: translation then rotation; their buttons still come as id 3.
// All axes are little-endian int16 counts, about +-350 at full deflection, in the HID frame: x to the
// right, y towards the user, z down (so pushing the cap in gives +z).
//
// The cap drives the placement at rates (slide, tilt), except the press, which follows the cap's
// push as a position: let go and the probe lifts off, as a real hand does when it relaxes.
#pragma once

#include <cstdint>
#include <span>

#include "device/device.hpp"

namespace echosim::device {

struct SpaceMouseState {
    std::int16_t tx = 0, ty = 0, tz = 0;  // translation [counts]; +tz: the cap pushed in
    std::int16_t rx = 0, ry = 0, rz = 0;  // rotation [counts]
    std::uint32_t buttons = 0;            // bit i: button i held
};

enum class SpaceMouseReport {
    translation,  // id 1, 7..12 bytes
    rotation,     // id 2
    motion,       // id 1, 13 bytes or more: translation and rotation
    buttons,      // id 3
    truncated,    // shorter than its id needs (the state is left as it was)
    unknown,      // an id we do not read (battery, LEDs, the Enterprise's keys; the state is left as it was)
};
const char* to_string(SpaceMouseReport r);

// Reads reports into the state it keeps, and counts the ones it could not use: a device that sends
// reports of another kind keeps working, and the driver can say so once.
class SpaceMouseParser {
public:
    SpaceMouseReport parse(std::span<const std::uint8_t> report) noexcept;

    const SpaceMouseState& state() const { return state_; }
    // back to rest (the device is gone: its last deflection means nothing any more)
    void reset() { state_ = {}; }
    std::uint64_t unknown_reports() const { return unknown_; }
    std::uint64_t truncated_reports() const { return truncated_; }

    static constexpr std::size_t kAxesReportBytes = 7;     // id + 3 x int16
    static constexpr std::size_t kMotionReportBytes = 13;  // id + 6 x int16

private:
    SpaceMouseState state_;
    std::uint64_t unknown_ = 0, truncated_ = 0;
};

// How the cap's deflection becomes motion over the skin.
struct SpaceMouseMapping {
    double dead_zone = 40;     // |axis| up to this gives nothing: the cap never rests exactly at 0 [counts]
    double sensitivity = 1.0;  // scales every rate and the press
    double full_scale = 350;   // a full deflection [counts]
    SurfaceLimits limits;      // where the slide may take the probe (the patch unless told)

    // at full deflection and sensitivity 1
    static constexpr double kSlidePerS = 0.25;            // across the exam patch [patch fraction / s]
    static constexpr double kTiltRadPerS = 0.5235987755982988;  // 30 degrees / s [rad/s]
    static constexpr double kTwistRadPerS = 1.5707963267948966; // the cap's twist: a quarter turn in 1 s [rad/s]
    static constexpr double kFullPressMm = 20.0;          // the cap pushed all the way in [mm]
};

// An axis as a fraction of full deflection in [-1, 1]: 0 within the dead zone, then growing from 0 at
// its edge (no jump as the cap leaves it) to 1 at full scale.
double deflection(std::int16_t counts, const SpaceMouseMapping& m) noexcept;

// What the state asks of the placement, in units.
struct SpaceMouseCommand {
    double du_per_s = 0, dv_per_s = 0;            // [patch fraction / s]
    double dfan_rad_per_s = 0, drock_rad_per_s = 0;  // [rad/s]
    double dtwist_rad_per_s = 0;                  // about the beam [rad/s]
    double press_mm = 0;                          // where the push puts the probe [mm], >= 0
    bool level = false;                           // button 0 held
};
// ty -> u (along the thigh), tx -> v (around it), rx -> fan, ry -> rock, +tz -> press, rz -> twist about the beam.
SpaceMouseCommand command_of(const SpaceMouseState& s, const SpaceMouseMapping& m) noexcept;

// The placement `dt_s` later, the state held meanwhile (clamped as device::moved clamps).
SurfacePlacement advanced(const SurfacePlacement& p, const SpaceMouseState& s, const SpaceMouseMapping& m, double dt_s) noexcept;

}  // namespace echosim::device

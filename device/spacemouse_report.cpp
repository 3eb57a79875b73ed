#include "device/spacemouse_report.hpp"

#include <algorithm>
#include <cmath>

#include "device/mouse_keyboard_device.hpp"

namespace echosim::device {
namespace {

constexpr std::uint8_t kTranslationId = 1, kRotationId = 2, kButtonsId = 3;

std::int16_t int16_at(std::span<const std::uint8_t> r, std::size_t i)
{
    return std::int16_t(std::uint16_t(r[i] | (unsigned(r[i + 1]) << 8)));
}

}  // namespace

const char* to_string(SpaceMouseReport r)
{
    switch (r) {
    case SpaceMouseReport::translation: return "translation";
    case SpaceMouseReport::rotation: return "rotation";
    case SpaceMouseReport::motion: return "motion";
    case SpaceMouseReport::buttons: return "buttons";
    case SpaceMouseReport::truncated: return "truncated";
    case SpaceMouseReport::unknown: return "unknown";
    }
    return "?";
}

SpaceMouseReport SpaceMouseParser::parse(std::span<const std::uint8_t> r) noexcept
{
    // every length is checked before a byte is read: hid_read hands over whatever the device sent
    if (r.empty()) {
        ++truncated_;
        return SpaceMouseReport::truncated;
    }
    switch (r[0]) {
    case kTranslationId:
        if (r.size() < kAxesReportBytes) break;
        state_.tx = int16_at(r, 1);
        state_.ty = int16_at(r, 3);
        state_.tz = int16_at(r, 5);
        // 8..12 bytes: the translation is whole, a rotation after it is not; use what is whole
        if (r.size() < kMotionReportBytes) return SpaceMouseReport::translation;
        state_.rx = int16_at(r, 7);
        state_.ry = int16_at(r, 9);
        state_.rz = int16_at(r, 11);
        return SpaceMouseReport::motion;
    case kRotationId:
        if (r.size() < kAxesReportBytes) break;
        state_.rx = int16_at(r, 1);
        state_.ry = int16_at(r, 3);
        state_.rz = int16_at(r, 5);
        return SpaceMouseReport::rotation;
    case kButtonsId: {
        if (r.size() < 2) break;
        // models with more than 32 buttons do not exist in this report form; bytes past 4 are ignored
        std::uint32_t mask = 0;
        const std::size_t n = std::min<std::size_t>(r.size() - 1, 4);
        for (std::size_t i = 0; i < n; ++i) mask |= std::uint32_t(r[1 + i]) << (8 * i);
        state_.buttons = mask;
        return SpaceMouseReport::buttons;
    }
    default:
        ++unknown_;
        return SpaceMouseReport::unknown;
    }
    ++truncated_;
    return SpaceMouseReport::truncated;
}

double deflection(std::int16_t counts, const SpaceMouseMapping& m) noexcept
{
    const double dead = std::max(m.dead_zone, 0.0);
    const double a = std::abs(double(counts));
    if (a <= dead) return 0.0;
    // measured from the dead zone's edge, so leaving it starts from 0; a full scale inside the dead
    // zone (a bad setting) still gives a bounded, monotonic answer
    const double span = std::max(m.full_scale - dead, 1.0);
    const double f = std::min((a - dead) / span, 1.0);
    return counts < 0 ? -f : f;
}

SpaceMouseCommand command_of(const SpaceMouseState& s, const SpaceMouseMapping& m) noexcept
{
    const double k = m.sensitivity;
    SpaceMouseCommand c;
    c.du_per_s = deflection(s.ty, m) * k * SpaceMouseMapping::kSlidePerS;
    c.dv_per_s = deflection(s.tx, m) * k * SpaceMouseMapping::kSlidePerS;
    c.dfan_rad_per_s = deflection(s.rx, m) * k * SpaceMouseMapping::kTiltRadPerS;
    c.drock_rad_per_s = deflection(s.ry, m) * k * SpaceMouseMapping::kTiltRadPerS;
    c.dtwist_rad_per_s = deflection(s.rz, m) * k * SpaceMouseMapping::kTwistRadPerS;
    // pulling the cap up cannot lift the probe off more than letting go does
    c.press_mm = std::max(deflection(s.tz, m), 0.0) * k * SpaceMouseMapping::kFullPressMm;
    c.level = (s.buttons & 1u) != 0;
    return c;
}

SurfacePlacement advanced(const SurfacePlacement& p, const SpaceMouseState& s, const SpaceMouseMapping& m, double dt_s) noexcept
{
    const SpaceMouseCommand c = command_of(s, m);
    SurfaceMotion motion;
    motion.du = c.du_per_s * dt_s;
    motion.dv = c.dv_per_s * dt_s;
    motion.dfan_rad = c.dfan_rad_per_s * dt_s;
    motion.drock_rad = c.drock_rad_per_s * dt_s;
    motion.dtwist_rad = c.dtwist_rad_per_s * dt_s;
    motion.press_mm = c.press_mm;
    motion.level = c.level;
    return moved(p, motion, m.limits);
}

}  // namespace echosim::device

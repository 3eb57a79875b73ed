#include "device/mouse_keyboard_device.hpp"

#include <algorithm>
#include <numbers>

namespace echosim::device {
namespace {

DeviceSample sample_of(const SurfacePlacement& p, std::uint64_t sequence)
{
    DeviceSample s;
    s.sequence = sequence;
    s.connected = true;
    s.control = Control::surface;
    s.surface = p;
    return s;
}

}  // namespace

SurfacePlacement moved(const SurfacePlacement& p, const SurfaceMotion& m, const SurfaceLimits& limits)
{
    constexpr double tilt = SurfacePlacement::kMaxTiltRad;
    SurfacePlacement q = p;
    q.u = std::clamp(p.u + m.du, limits.u_lo, limits.u_hi);
    q.v = std::clamp(p.v + m.dv, limits.v_lo, limits.v_hi);
    q.twist_rad = std::clamp(p.twist_rad + m.dtwist_rad, 0.0, std::numbers::pi / 2);
    if (m.turn) q.twist_rad = q.twist_rad == 0.0 ? std::numbers::pi / 2 : 0.0;
    q.fan_rad = m.level ? 0.0 : std::clamp(p.fan_rad + m.dfan_rad, -tilt, tilt);
    q.rock_rad = m.level ? 0.0 : std::clamp(p.rock_rad + m.drock_rad, -tilt, tilt);
    q.press_mm = std::clamp(m.press_mm.value_or(p.press_mm + m.dpress_mm), 0.0, SurfacePlacement::kMaxPressMm);
    return q;
}

MouseKeyboardDevice::MouseKeyboardDevice(const SurfacePlacement& start, const SurfaceLimits& limits)
    : limits_(limits), placement_(moved(start, {}, limits)), handoff_(sample_of(placement_, 0))
{
    caps_.name = "mouse and keyboard";
    caps_.driver = "GLFW window";
    caps_.address = "the simulator's window";
    caps_.control = Control::surface;
    caps_.degrees_of_freedom = 5;  // slide (2), tilt (2), press
    caps_.buttons = 2;
}

const SurfacePlacement& MouseKeyboardDevice::feed(const SurfaceMotion& m)
{
    placement_ = moved(placement_, m, limits_);
    handoff_.write_slot() = sample_of(placement_, ++fed_);
    handoff_.publish();
    return placement_;
}

bool MouseKeyboardDevice::read(double, DeviceSample& out) noexcept
{
    out = handoff_.read();
    return true;
}

void MouseKeyboardDevice::events(std::vector<DeviceEvent>& out)
{
    if (announced_) return;
    announced_ = true;
    out.push_back({DeviceEvent::Kind::connected, caps_.name,
                   "right-drag or arrows slide the probe, Q/E fan it, A/D rock it, R levels it, W/S or Shift+wheel press it"});
}

}  // namespace echosim::device

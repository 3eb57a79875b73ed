// The mouse and keyboard of the simulator's window, as a device: the probe slides over the skin,
// tilts and presses in. The window's thread turns GLFW's input into SurfaceMotion (which keys and
// drags do what: engine/app/window_input.hpp) and feeds it here once a frame; the haptic thread reads
// the placement it adds up to, through a lock-free triple buffer. No force feedback: the force shows
// on the screen instead.
#pragma once

#include <optional>

#include "core/triple_buffer.hpp"
#include "device/device.hpp"

namespace echosim::device {

// What the user did since the last frame.
struct SurfaceMotion {
    double du = 0, dv = 0;               // slide over the exam patch (fractions of its extent)
    double dfan_rad = 0, drock_rad = 0;  // tilt
    double dpress_mm = 0;                // press in (negative: lift)
    std::optional<double> press_mm;      // an absolute press, which wins over dpress_mm [mm]
    bool level = false;                  // back upright (no tilt)
    bool turn = false;                   // a quarter turn about the beam: transverse <-> longitudinal
    double dtwist_rad = 0;               // a twist about the beam, kept within [0, pi/2] [rad]
};

class MouseKeyboardDevice : public Device {
public:
    explicit MouseKeyboardDevice(const SurfacePlacement& start = {}, const SurfaceLimits& limits = {});

    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d&) noexcept override {}
    void events(std::vector<DeviceEvent>& out) override;

    // Window thread: adds the motion up (clamped to the patch, the tilt and the press limits) and
    // hands the placement over. Returns it.
    const SurfacePlacement& feed(const SurfaceMotion& m);
    const SurfacePlacement& placement() const { return placement_; }  // window thread

private:
    Capabilities caps_;
    SurfaceLimits limits_;
    SurfacePlacement placement_;              // the window thread's
    std::uint64_t fed_ = 0;                   // the window thread's
    TripleBuffer<DeviceSample> handoff_;      // window thread -> haptic thread
    bool announced_ = false;
};

// The placement after `m`, clamped to `limits`, the tilt and the press (as MouseKeyboardDevice::feed
// clamps); the twist is kept between transverse (0) and longitudinal (pi/2), and a turn sets it to
// transverse from anything but that, else to longitudinal.
SurfacePlacement moved(const SurfacePlacement& p, const SurfaceMotion& m, const SurfaceLimits& limits = {});

}  // namespace echosim::device

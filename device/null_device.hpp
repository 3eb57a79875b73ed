// The null device: no hand on the probe. It rests on the middle of the exam patch, touching the skin
// without pressing, for ever; it takes any force and feels nothing. What a session drives when it
// has no device (a headless check of the loop, a kiosk whose device is gone and not yet back).
#pragma once

#include "device/device.hpp"

namespace echosim::device {

class NullDevice : public Device {
public:
    NullDevice();
    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d&) noexcept override {}
    void events(std::vector<DeviceEvent>&) override {}

private:
    Capabilities caps_;
};

}  // namespace echosim::device

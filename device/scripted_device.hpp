// The scripted driver: a trajectory (device/trajectory.hpp) played on the haptic loop's clock, the
// same way every run, for tests, benchmarks and headless exams. Its samples are world poses; the
// forces the loop sends it are kept, so a run can be checked against what a hand would have felt.
// Played once, it holds its last pose; looped, it starts over from its first row when it reaches
// its last, the last row's time being the next round's first (a loop whose last pose is its first,
// such as app/haptics_demo.hpp's round trip, plays on without a jump, for as long as a soak lasts).
#pragma once

#include <atomic>

#include "device/device.hpp"
#include "device/trajectory.hpp"

namespace echosim::device {

class ScriptedDevice : public Device {
public:
    // `name` is what `echosim devices` and the log call it (the file it came from, say)
    enum class Playback { once, loop };
    ScriptedDevice(Trajectory trajectory, std::string name, Playback playback = Playback::once);

    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d& force_N) noexcept override { last_force_ = force_N; }
    void events(std::vector<DeviceEvent>& out) override;

    const Trajectory& trajectory() const { return trajectory_; }
    // the last force the loop sent (read it from the haptic thread, or once the loop has stopped)
    const Eigen::Vector3d& last_force() const { return last_force_; }

private:
    Trajectory trajectory_;
    Playback playback_;
    Capabilities caps_;
    std::uint64_t sequence_ = 0;
    Eigen::Vector3d last_force_ = Eigen::Vector3d::Zero();
    bool announced_ = false;
};

}  // namespace echosim::device

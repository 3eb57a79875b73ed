// A probe held by the program: a world-pose device (as a scripted trajectory gives poses) whose pose
// its owner sets, and which remembers the forces it was sent: the tests' hand, the e2e benchmark's.
// Thread hand-off: the owner's thread calls move_to; the haptic loop's thread calls read and
// write_force; the pose behind a mutex, the force and its count atomics.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/pose.hpp"
#include "device/device.hpp"

namespace echosim::device {

class HeldDevice final : public Device {
public:
    HeldDevice(const Pose& start, std::string name)
    {
        caps_.name = std::move(name);
        caps_.driver = "test";
        caps_.control = Control::world;
        caps_.max_force_N = 20;
        move_to(start);
    }
    void move_to(const Pose& p)
    {
        const std::lock_guard lock(mutex_);
        sample_.control = Control::world;
        sample_.connected = true;
        sample_.position = {p.position.x, p.position.y, p.position.z};
        sample_.orientation = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized();
    }
    const Capabilities& capabilities() const override { return caps_; }
    bool read(double, DeviceSample& out) noexcept override
    {
        const std::lock_guard lock(mutex_);
        ++sample_.sequence;
        out = sample_;
        return true;
    }
    void write_force(const Eigen::Vector3d& f) noexcept override
    {
        last_N_.store(f.norm());
        writes_.fetch_add(1);
    }
    void events(std::vector<DeviceEvent>&) override {}

    double last_force_N() const { return last_N_.load(); }
    long writes() const { return writes_.load(); }

private:
    Capabilities caps_;
    std::mutex mutex_;
    DeviceSample sample_;
    std::atomic<double> last_N_{-1};
    std::atomic<long> writes_{0};
};

}  // namespace echosim::device

// A hand the test holds the probe with: a world-pose device (as a scripted trajectory gives poses)
// whose pose the test sets and which remembers the forces it was sent. Thread hand-off: the test
// thread calls move_to; the haptic loop's thread calls read and write_force; the pose behind a
// mutex, the force and its count atomics.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/pose.hpp"
#include "device/device.hpp"

namespace echosim::test {

class HeldHand final : public device::Device {
public:
    HeldHand(const Pose& start, std::string name)
    {
        caps_.name = std::move(name);
        caps_.driver = "test";
        caps_.control = device::Control::world;
        caps_.max_force_N = 20;
        move_to(start);
    }
    void move_to(const Pose& p)
    {
        const std::lock_guard lock(mutex_);
        sample_.control = device::Control::world;
        sample_.connected = true;
        sample_.position = {p.position.x, p.position.y, p.position.z};
        sample_.orientation = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized();
    }
    const device::Capabilities& capabilities() const override { return caps_; }
    bool read(double, device::DeviceSample& out) noexcept override
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
    void events(std::vector<device::DeviceEvent>&) override {}

    double last_force_N() const { return last_N_.load(); }
    long writes() const { return writes_.load(); }

private:
    device::Capabilities caps_;
    std::mutex mutex_;
    device::DeviceSample sample_;
    std::atomic<double> last_N_{-1};
    std::atomic<long> writes_{0};
};

}  // namespace echosim::test

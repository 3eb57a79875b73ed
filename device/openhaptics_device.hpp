// 3D Systems' Touch and Phantom arms through OpenHaptics' HD API (device/openhaptics_api.hpp, loaded
// at run time) as a device: the handle's pose in, a force out, with the workspace and limits of
// device/README.md ("A force-feedback arm behind the same interface").
//
// Threads. OpenHaptics runs its own 1 kHz servo thread (hdStartScheduler); our asynchronous callback
// on it opens a frame, reads the handle's transform and buttons, sends the force the haptic loop
// asked for last, closes the frame and checks hdGetError. The haptic thread never calls the HD API:
// read() takes the servo's latest sample and write_force() leaves the force for its next frame, each
// through a triple buffer, so neither side waits for the other. The driver thread's events() turns
// what the servo saw (a fault, a recovery, an error such as a force the arm cut) into events.
//
// Safety. The force sent is cut to the arm's continuous maximum (its nominal peak, where it reports
// no continuous figure), keeping its direction; a NaN sends nothing. A force the loop has not
// renewed for kForceHoldS (a stopped or stalled loop) is replaced by zero, so the arm never
// holds a push nobody computes. Destroying the device sends zero force in a frame of its own, stops
// the scheduler and disables force output and the device, in that order.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "core/triple_buffer.hpp"
#include "device/device.hpp"
#include "device/openhaptics_api.hpp"

namespace echosim::device {

class OpenHapticsDevice : public Device {
public:
    // Opens OpenHaptics' default device (HD_DEFAULT_DEVICE) through `api` and starts its servo.
    // Throws std::runtime_error naming the HD error (hdGetError) and what to check when the arm
    // cannot be opened or reports limits it cannot have; nothing is left running then.
    explicit OpenHapticsDevice(std::shared_ptr<const hd::HdApi> api);
    ~OpenHapticsDevice() override;
    OpenHapticsDevice(const OpenHapticsDevice&) = delete;
    OpenHapticsDevice& operator=(const OpenHapticsDevice&) = delete;

    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d& force_N) noexcept override;
    void events(std::vector<DeviceEvent>& out) override;

private:
    struct Command {
        Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
        std::int64_t stamp_ns = 0;  // steady clock; 0: never sent
    };
    static hd::HDCallbackCode servo(void* self) noexcept;
    static hd::HDCallbackCode send_zero(void* self) noexcept;
    hd::HDCallbackCode servo_frame(bool zero_only) noexcept;

    std::shared_ptr<const hd::HdApi> api_;
    hd::HHD hhd_ = hd::HD_INVALID_HANDLE;
    hd::HDSchedulerHandle callback_ = 0;
    Capabilities caps_;
    Eigen::Vector3d centre_mm_ = Eigen::Vector3d::Zero();  // the usable box's centre: our workspace origin
    // servo thread's own
    std::uint64_t sequence_ = 0;
    DeviceSample servo_sample_;
    // hand-offs
    TripleBuffer<DeviceSample> state_;  // servo thread -> haptic thread
    TripleBuffer<Command> command_;     // haptic thread -> servo thread
    std::atomic<bool> stopping_{false};
    // what the servo saw, for events() (driver thread)
    std::atomic<bool> connected_{true};
    std::atomic<std::uint32_t> fault_code_{0};
    std::atomic<int> fault_internal_{0};
    std::atomic<std::uint64_t> frame_errors_{0};  // errors other than faults
    std::atomic<std::uint32_t> frame_error_code_{0};
    // driver thread's own
    bool announced_ = false, reported_connected_ = true;
    std::uint64_t reported_frame_errors_ = 0;
};

// What `echosim devices` says of an arm: whether OpenHaptics is installed, and if so whether an arm
// answers. Opens the arm to ask and disables it again; starts no servo and sends no force.
struct OpenHapticsProbe {
    bool library_found = false;
    bool available = false;
    Capabilities capabilities;  // the arm's when available, else the Touch's figures from device/README.md
    std::string status;         // a sentence: ready, or why not and what to do
};
OpenHapticsProbe probe_openhaptics(const hd::HdLoad& load);
OpenHapticsProbe probe_openhaptics();  // through load_hd_library()

}  // namespace echosim::device

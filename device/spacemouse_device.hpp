// A 3Dconnexion SpaceMouse as a device: its cap slides, tilts and presses the probe over the skin
// (device/spacemouse_report.hpp says how). Six degrees of freedom in, no force out.
//
// Threads. HID reads block, and finding and opening a device allocates, so a reader thread of the
// driver's own does all of it: it finds a SpaceMouse, opens it, reads its reports (waking at least
// every kReadTimeoutMs, which bounds how long the destructor waits), integrates the placement
// between reads on the steady clock, and hands each new sample to the haptic thread through a
// triple buffer. Connection changes travel to the driver thread through an EventQueue.
//
// Hot-plug. A failed read means the device is gone: the driver says so, publishes a sample marked
// not connected, with the last placement but no press (the hand that let go of the cap has lifted
// the probe off), and looks for a device again every kRetryS. When one comes back, the probe goes on
// from where it was over the skin. A device present but not ours to read gets one access_denied
// event naming the udev rule that fixes it, not one a second.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "core/triple_buffer.hpp"
#include "device/device.hpp"
#include "device/event_queue.hpp"
#include "device/hid_devices.hpp"
#include "device/spacemouse_report.hpp"

namespace echosim::device {

class SpaceMouseDevice : public Device {
public:
    // Never throws for want of a device: with none present it keeps looking, and events() says so.
    explicit SpaceMouseDevice(const SpaceMouseMapping& mapping = {}, const SurfacePlacement& start = {});
    // the same over another backend (a test's fake)
    SpaceMouseDevice(std::shared_ptr<HidBackend> backend, const SpaceMouseMapping& mapping = {}, const SurfacePlacement& start = {});
    ~SpaceMouseDevice() override;
    SpaceMouseDevice(const SpaceMouseDevice&) = delete;
    SpaceMouseDevice& operator=(const SpaceMouseDevice&) = delete;

    // The device present when this was made, or the family's description if none was: capabilities
    // are fixed for the device's life, and the model plugged in later is named by its events.
    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d&) noexcept override {}
    void events(std::vector<DeviceEvent>& out) override;

    static constexpr int kReadTimeoutMs = 20;
    static constexpr double kRetryS = 1.0;
    // the longest step the placement integrates at once [s]: a thread held up (a suspended laptop)
    // must not carry the probe across the patch on a deflection it saw long ago
    static constexpr double kMaxStepS = 0.1;

private:
    void run(SurfacePlacement placement) noexcept;
    void publish(const SurfacePlacement& p, bool connected, std::uint32_t buttons);
    // waits `seconds` or until the destructor asks the thread to stop; true: stop
    bool wait_or_stop(double seconds);

    std::shared_ptr<HidBackend> backend_;
    SpaceMouseMapping mapping_;
    Capabilities caps_;
    std::uint64_t sequence_ = 0;            // the reader thread's
    TripleBuffer<DeviceSample> handoff_;    // reader thread -> haptic thread
    EventQueue events_;                     // reader thread -> driver thread
    std::mutex stop_mutex_;
    std::condition_variable stop_cv_;
    std::atomic<bool> stop_{false};
    std::thread reader_;  // last: it starts once everything above is made
};

}  // namespace echosim::device

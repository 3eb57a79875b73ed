// Connection events on their way from a driver's own thread (the HID reader, which finds, opens and
// loses devices) to the session's driver thread, which logs them and shows them in the window. A
// mutex guards it: neither side is the haptic thread, which never touches it.
#pragma once

#include <mutex>
#include <vector>

#include "device/device.hpp"

namespace echosim::device {

class EventQueue {
public:
    void push(DeviceEvent e)
    {
        const std::lock_guard lock(mutex_);
        pending_.push_back(std::move(e));
    }
    // appends what came since the last call, oldest first
    void drain(std::vector<DeviceEvent>& out)
    {
        const std::lock_guard lock(mutex_);
        for (DeviceEvent& e : pending_) out.push_back(std::move(e));
        pending_.clear();
    }

private:
    std::mutex mutex_;
    std::vector<DeviceEvent> pending_;
};

}  // namespace echosim::device

// A HID backend with devices a test makes up: plug and unplug them, queue their reports, refuse to
// open them as a node without the udev rule would. Read blocks like hid_read_timeout (up to its
// timeout, or until a report or an unplug), so the driver under test runs its real loop.
#pragma once

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "device/hid_devices.hpp"

namespace echosim::device::test {

class FakeHidBackend : public HidBackend {
public:
    static constexpr const char* kReadError = "hid_read_timeout: unexpected poll error (device disconnected)";

    struct Node {
        HidDeviceInfo info;
        bool present = true;
        bool denied = false;  // open fails with EACCES
    };

    explicit FakeHidBackend(std::vector<Node> nodes) : nodes_(std::move(nodes)) {}

    // test side
    void unplug(std::size_t i)
    {
        const std::lock_guard lock(mutex_);
        nodes_[i].present = false;
        reports_.clear();
        changed_.notify_all();
    }
    void plug(std::size_t i)
    {
        const std::lock_guard lock(mutex_);
        nodes_[i].present = true;
    }
    void allow(std::size_t i)
    {
        const std::lock_guard lock(mutex_);
        nodes_[i].denied = false;
    }
    void send(std::vector<std::uint8_t> report)
    {
        const std::lock_guard lock(mutex_);
        reports_.push_back(std::move(report));
        changed_.notify_all();
    }
    int open_attempts() const
    {
        const std::lock_guard lock(mutex_);
        return open_attempts_;
    }
    int open_handles() const
    {
        const std::lock_guard lock(mutex_);
        return open_handles_;
    }

    // driver side
    std::vector<HidDeviceInfo> enumerate() override
    {
        const std::lock_guard lock(mutex_);
        std::vector<HidDeviceInfo> out;
        for (const Node& n : nodes_)
            if (n.present) out.push_back(n.info);
        return out;
    }
    HidOpenResult open(const std::string& path) override
    {
        const std::lock_guard lock(mutex_);
        ++open_attempts_;
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            const Node& n = nodes_[i];
            if (n.info.path != path || !n.present) continue;
            if (n.denied) return {nullptr, EACCES, "Failed to open a device with path '" + path + "': Permission denied"};
            ++open_handles_;
            opened_ = i;
            return {&handle_, 0, {}};
        }
        return {nullptr, ENOENT, "Failed to open a device with path '" + path + "': No such file or directory"};
    }
    int read(void*, std::uint8_t* buffer, std::size_t size, int timeout_ms) override
    {
        std::unique_lock lock(mutex_);
        changed_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                          [&] { return !nodes_[opened_].present || !reports_.empty(); });
        if (!nodes_[opened_].present) return -1;
        if (reports_.empty()) return 0;
        const std::vector<std::uint8_t> r = std::move(reports_.front());
        reports_.pop_front();
        const std::size_t n = std::min(size, r.size());
        std::memcpy(buffer, r.data(), n);
        return int(n);
    }
    std::string last_error(void*) override { return kReadError; }
    void close(void*) override
    {
        const std::lock_guard lock(mutex_);
        --open_handles_;
    }

private:
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<Node> nodes_;
    std::deque<std::vector<std::uint8_t>> reports_;
    std::size_t opened_ = 0;
    int open_attempts_ = 0, open_handles_ = 0;
    int handle_ = 0;  // its address is the handle
};

}  // namespace echosim::device::test

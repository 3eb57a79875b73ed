#include "device/spacemouse_device.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "device/mouse_keyboard_device.hpp"

namespace echosim::device {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kHowTo =
    "slide the cap to slide the probe, tilt it forward and back to fan and sideways to rock, push it down to press "
    "(let go and the probe lifts); the left button levels it";

// Until the reader thread finds a device, the haptic thread reads "not connected", resting at the
// start without a press (no hand on the cap yet).
DeviceSample resting_sample(const SurfacePlacement& start, const SurfaceLimits& limits)
{
    DeviceSample s;
    s.connected = false;
    s.control = Control::surface;
    s.surface = moved(start, {}, limits);
    s.surface.press_mm = 0;
    return s;
}

bool same(const SurfacePlacement& a, const SurfacePlacement& b)
{
    return a.u == b.u && a.v == b.v && a.fan_rad == b.fan_rad && a.rock_rad == b.rock_rad && a.press_mm == b.press_mm;
}

std::string hex2(unsigned v)
{
    char s[8];
    std::snprintf(s, sizeof s, "0x%02x", v & 0xffu);
    return s;
}

}  // namespace

SpaceMouseDevice::SpaceMouseDevice(const SpaceMouseMapping& mapping, const SurfacePlacement& start)
    : SpaceMouseDevice(hidapi_backend(), mapping, start)
{
}

SpaceMouseDevice::SpaceMouseDevice(std::shared_ptr<HidBackend> backend, const SpaceMouseMapping& mapping, const SurfacePlacement& start)
    : backend_(std::move(backend)), mapping_(mapping), caps_(spacemouse_family_capabilities()), handoff_(resting_sample(start, mapping.limits))
{
    // named after what is plugged in now, if anything; the reader thread does the opening
    if (const std::vector<FoundDevice> found = find_spacemice(*backend_, false); !found.empty()) caps_ = found.front().capabilities;
    reader_ = std::thread([this, start] { run(resting_sample(start, mapping_.limits).surface); });
}

SpaceMouseDevice::~SpaceMouseDevice()
{
    {
        const std::lock_guard lock(stop_mutex_);
        stop_ = true;
    }
    stop_cv_.notify_all();
    reader_.join();
}

bool SpaceMouseDevice::read(double, DeviceSample& out) noexcept
{
    out = handoff_.read();
    return out.connected;
}

void SpaceMouseDevice::events(std::vector<DeviceEvent>& out)
{
    events_.drain(out);
}

void SpaceMouseDevice::publish(const SurfacePlacement& p, bool connected, std::uint32_t buttons)
{
    DeviceSample& s = handoff_.write_slot();
    s.sequence = ++sequence_;
    s.connected = connected;
    s.control = Control::surface;
    s.surface = p;
    s.buttons = buttons;
    handoff_.publish();
}

bool SpaceMouseDevice::wait_or_stop(double seconds)
{
    std::unique_lock lock(stop_mutex_);
    return stop_cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return stop_.load(); });
}

void SpaceMouseDevice::run(SurfacePlacement placement) noexcept
{
    void* handle = nullptr;
    std::string name = caps_.name;
    try {
        SpaceMouseParser parser;
        std::array<std::uint8_t, 64> buffer{};  // a full-speed HID report's most; the family sends 13 at most
        std::vector<std::string> refused;       // nodes we said we cannot open: said once while they stay
        bool said_missing = false, said_unknown = false;
        Clock::time_point last = Clock::now();

        while (!stop_) {
            if (handle == nullptr) {
                const std::vector<FoundDevice> found = find_spacemice(*backend_, false);
                std::erase_if(refused, [&](const std::string& path) {
                    return std::none_of(found.begin(), found.end(), [&](const FoundDevice& f) { return f.hid.path == path; });
                });
                for (const FoundDevice& f : found) {
                    const HidOpenResult r = backend_->open(f.hid.path);
                    if (r.handle != nullptr) {
                        handle = r.handle;
                        name = f.capabilities.name;
                        events_.push({DeviceEvent::Kind::connected, name, f.hid.path + ": " + kHowTo});
                        break;
                    }
                    if (std::find(refused.begin(), refused.end(), f.hid.path) != refused.end()) continue;
                    refused.push_back(f.hid.path);
                    if (is_access_denied(r))
                        events_.push({DeviceEvent::Kind::access_denied, f.capabilities.name, access_denied_message(f.hid.path)});
                    else
                        events_.push({DeviceEvent::Kind::note, f.capabilities.name,
                                      "cannot open " + f.hid.path + ": " + r.error + "; trying again every second"});
                }
                if (handle == nullptr) {
                    if (found.empty() && !said_missing) {
                        said_missing = true;
                        events_.push({DeviceEvent::Kind::note, caps_.name,
                                      "no 3Dconnexion device found (vendor 046d/256f); plug one in and it is picked up within a second"});
                    }
                    if (wait_or_stop(kRetryS)) break;
                    continue;
                }
                // a new connection starts from rest: the cap's last deflection went with the old one
                parser.reset();
                placement = advanced(placement, parser.state(), mapping_, 0.0);
                publish(placement, true, 0);
                last = Clock::now();
            }

            const int n = backend_->read(handle, buffer.data(), buffer.size(), kReadTimeoutMs);
            const Clock::time_point now = Clock::now();
            const double dt = std::min(std::chrono::duration<double>(now - last).count(), kMaxStepS);
            last = now;

            if (n < 0) {
                const std::string why = backend_->last_error(handle);
                backend_->close(handle);
                handle = nullptr;
                parser.reset();
                // the cap let go: no press, but the probe stays where it was over the skin
                placement.press_mm = 0;
                publish(placement, false, 0);
                events_.push({DeviceEvent::Kind::disconnected, name, "read failed: " + why + "; looking for it again"});
                said_missing = true;  // the event above already says we are looking
                if (wait_or_stop(kRetryS)) break;
                continue;
            }

            // the state held since the last read moved the probe until now; a new report takes over
            // from here, its press at once (a position, not a rate)
            SurfacePlacement next = advanced(placement, parser.state(), mapping_, dt);
            bool report = false;
            if (n > 0) {
                const std::size_t size = std::min(std::size_t(n), buffer.size());
                const SpaceMouseReport kind = parser.parse({buffer.data(), size});
                report = kind != SpaceMouseReport::truncated && kind != SpaceMouseReport::unknown;
                if (kind == SpaceMouseReport::unknown && !said_unknown) {
                    said_unknown = true;
                    events_.push({DeviceEvent::Kind::note, name,
                                  "sends reports with id " + hex2(buffer[0]) + " (" + std::to_string(size) +
                                      " bytes), which we do not read; the cap still works"});
                }
                next = advanced(next, parser.state(), mapping_, 0.0);
            }
            if (report || !same(next, placement)) {
                placement = next;
                publish(placement, true, parser.state().buttons);
            }
        }
    } catch (const std::exception& e) {
        // nothing may escape a thread: the device stops (the probe lifts off) and says why if it can
        placement.press_mm = 0;
        publish(placement, false, 0);
        try {
            events_.push({DeviceEvent::Kind::disconnected, name, std::string("stopped: ") + e.what()});
        } catch (...) {
        }
    } catch (...) {
        placement.press_mm = 0;
        publish(placement, false, 0);
    }
    if (handle != nullptr) backend_->close(handle);
}

}  // namespace echosim::device

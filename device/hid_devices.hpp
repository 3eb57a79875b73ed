// HID devices we can drive (3Dconnexion's SpaceMouse family), found and described the same way for
// the driver (device/spacemouse_device.hpp) and for `echosim devices`.
//
// The HID I/O sits behind HidBackend, four calls wide, so that a test can stand a fake device in for
// a real one, make it vanish and come back, or refuse to open. The real backend is hidapi over
// Linux hidraw. hidapi wants hid_init before its first use and hid_exit after its last, once per
// process; each real backend holds a reference on a process-wide count for that
// (hidapi_backend.cpp), the one piece of global mutable state in the device layer.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/device.hpp"

namespace echosim::device {

struct HidDeviceInfo {
    std::string path;  // what open() takes: /dev/hidrawN
    std::uint16_t vendor_id = 0, product_id = 0;
    std::string product;  // the device's own product string (may be empty)
    std::string serial;
};

struct HidOpenResult {
    void* handle = nullptr;  // opaque to the caller; null: it failed, and why is below
    int error_code = 0;      // an errno value where the backend knows it (EACCES, ENOENT), else 0
    std::string error;       // the backend's words
};

class HidBackend {
public:
    virtual ~HidBackend() = default;
    // every HID device present now
    virtual std::vector<HidDeviceInfo> enumerate() = 0;
    virtual HidOpenResult open(const std::string& path) = 0;
    // hid_read_timeout's contract: the report's bytes (id first) or 0 after `timeout_ms` without
    // one, -1 when the device failed (unplugged); then last_error() says why
    virtual int read(void* handle, std::uint8_t* buffer, std::size_t size, int timeout_ms) = 0;
    virtual std::string last_error(void* handle) = 0;
    virtual void close(void* handle) = 0;
};

// hidapi over hidraw. Never throws: if hid_init fails, enumerate() finds nothing and open() says why.
std::shared_ptr<HidBackend> hidapi_backend();

inline constexpr std::uint16_t kLogitechVendorId = 0x046d;      // 3Dconnexion's older devices
inline constexpr std::uint16_t kThreeDconnexionVendorId = 0x256f;

// Ours to drive: any 3Dconnexion product, and the 3Dconnexion products sold under Logitech's vendor id
// (which also covers Logitech's own mice and keyboards: those are not ours).
bool is_spacemouse(std::uint16_t vendor_id, std::uint16_t product_id);

struct FoundDevice {
    Capabilities capabilities;
    HidDeviceInfo hid;
    bool access_checked = false;  // whether accessible and reason below say anything
    bool accessible = false;      // it opened (and was closed again)
    std::string reason;           // when not accessible: why, and what to do about it
};

// What any SpaceMouse can do, before we know which one it is: six degrees of freedom over the skin,
// two buttons, no force. find_spacemice fills in the rest from the device.
Capabilities spacemouse_family_capabilities();

// The SpaceMice present now, one entry per device node, in enumeration order. With `check_access`,
// each is opened and closed to see whether this user may read it.
std::vector<FoundDevice> find_spacemice(HidBackend& backend, bool check_access = true);

// What we know of a model that its HID descriptor does not say: a name for when it sends no product
// string, and its button count (2, the two side buttons every model has, for the ones not listed).
struct SpaceMouseModel {
    const char* name;
    int buttons;
};
SpaceMouseModel spacemouse_model(std::uint16_t product_id);

// The HID backend could not open `error`'s device because this user may not read its node.
bool is_access_denied(const HidOpenResult& error);
// The sentence a user sees then: which node, and the commands that fix it.
std::string access_denied_message(const std::string& path);

inline constexpr const char* kUdevRuleFile = "device/udev/70-echosim-spacemouse.rules";

}  // namespace echosim::device

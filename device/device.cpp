#include "device/device.hpp"

namespace echosim::device {

const char* to_string(Control c)
{
    switch (c) {
    case Control::surface: return "surface (slide, tilt, press over the skin)";
    case Control::workspace: return "workspace (a handle's pose, mapped onto the patient)";
    case Control::world: return "world (the probe's pose as given)";
    }
    return "?";
}

const char* to_string(DeviceEvent::Kind k)
{
    switch (k) {
    case DeviceEvent::Kind::connected: return "connected";
    case DeviceEvent::Kind::disconnected: return "disconnected";
    case DeviceEvent::Kind::access_denied: return "access denied";
    case DeviceEvent::Kind::note: return "note";
    }
    return "?";
}

}  // namespace echosim::device

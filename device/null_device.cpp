#include "device/null_device.hpp"

namespace echosim::device {

NullDevice::NullDevice()
{
    caps_.name = "no device";
    caps_.driver = "null";
    caps_.address = "-";
    caps_.control = Control::surface;
}

bool NullDevice::read(double, DeviceSample& out) noexcept
{
    out = DeviceSample{};
    out.sequence = 1;
    out.connected = true;
    return true;
}

}  // namespace echosim::device

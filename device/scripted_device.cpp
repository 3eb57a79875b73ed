#include "device/scripted_device.hpp"

namespace echosim::device {

ScriptedDevice::ScriptedDevice(Trajectory trajectory, std::string name) : trajectory_(std::move(trajectory))
{
    caps_.name = "scripted trajectory";
    caps_.driver = "scripted";
    caps_.address = std::move(name);
    caps_.control = Control::world;
    caps_.degrees_of_freedom = 6;
}

bool ScriptedDevice::read(double t_s, DeviceSample& out) noexcept
{
    const TrajectoryRow r = trajectory_.at(t_s);
    out.sequence = ++sequence_;
    out.connected = true;
    out.control = Control::world;
    out.position = r.position;
    out.orientation = r.orientation;
    out.buttons = 0;
    return true;
}

void ScriptedDevice::events(std::vector<DeviceEvent>& out)
{
    if (announced_) return;
    announced_ = true;
    out.push_back({DeviceEvent::Kind::connected, caps_.name,
                   caps_.address + ": " + std::to_string(trajectory_.rows().size()) + " poses over " +
                       std::to_string(trajectory_.end_s() - trajectory_.start_s()) + " s"});
}

}  // namespace echosim::device

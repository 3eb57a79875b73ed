#include "device/scripted_device.hpp"

#include <cmath>

namespace echosim::device {

ScriptedDevice::ScriptedDevice(Trajectory trajectory, std::string name, Playback playback)
    : trajectory_(std::move(trajectory)), playback_(playback)
{
    caps_.name = "scripted trajectory";
    caps_.driver = "scripted";
    caps_.address = std::move(name);
    caps_.control = Control::world;
    caps_.degrees_of_freedom = 6;
}

bool ScriptedDevice::read(double t_s, DeviceSample& out) noexcept
{
    const double start = trajectory_.start_s(), length = trajectory_.end_s() - start;
    if (playback_ == Playback::loop && length > 0 && t_s > start) t_s = start + std::fmod(t_s - start, length);
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
                       std::to_string(trajectory_.end_s() - trajectory_.start_s()) + " s" +
                       (playback_ == Playback::loop ? ", looped" : "")});
}

}  // namespace echosim::device

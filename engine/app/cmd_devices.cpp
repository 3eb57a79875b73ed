// `echosim devices`: the input and haptic devices echosim can drive, what each can do, and whether it
// is ready, so a user learns before a session why the SpaceMouse on the desk does nothing.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "device/hid_devices.hpp"
#include "device/mouse_keyboard_device.hpp"
#include "device/null_device.hpp"
#include "device/openhaptics_device.hpp"
#include "device/scripted_device.hpp"
#include "device/simulated_arm.hpp"

namespace echosim::app {
namespace {

struct Listed {
    device::Capabilities caps;
    bool available = false;
    std::string status;  // when it can be used, or why not and what to do
    const device::FoundDevice* hid = nullptr;
    const device::OpenHapticsProbe* arm = nullptr;
};

const char* control_name(device::Control c)
{
    switch (c) {
    case device::Control::surface: return "surface";
    case device::Control::workspace: return "workspace";
    case device::Control::world: return "world";
    }
    return "?";
}

std::string force_text(const device::Capabilities& c)
{
    if (!c.has_force()) return "none";
    char s[96];
    std::snprintf(s, sizeof s, "%.2f N, %.2f N/mm", c.max_force_N, c.max_stiffness_N_per_mm);
    return s;
}

std::string hex4(std::uint16_t v)
{
    char s[8];
    std::snprintf(s, sizeof s, "%04x", unsigned(v));
    return s;
}

}  // namespace

int run_devices(const DevicesArgs& args)
{
    // the drivers' own capabilities, not a copy of them: made here only to be described
    std::vector<Listed> listed;
    listed.push_back({device::MouseKeyboardDevice().capabilities(), true,
                      "available when the simulator has a window (echosim run)"});
    listed.push_back({device::NullDevice().capabilities(), true, "always available: the probe rests on the patch centre"});
    const device::ScriptedDevice scripted(
        device::Trajectory::parse(std::string(device::Trajectory::kHeader) + "\n0,0,0,0,1,0,0,0\n", "example"), "a trajectory CSV");
    listed.push_back({scripted.capabilities(), true, "give a trajectory CSV (--trajectory F.csv)"});
    listed.push_back({device::SimulatedArm().capabilities(), true,
                      "always available (echosim run --device simulated-arm): a simulated hand presses a simulated arm"});

    // a Touch/Phantom through OpenHaptics, if its library is installed and an arm answers
    const device::OpenHapticsProbe arm = device::probe_openhaptics();
    listed.push_back({arm.capabilities, arm.available, arm.status, nullptr, &arm});

    const std::shared_ptr<device::HidBackend> hid = device::hidapi_backend();
    const std::vector<device::FoundDevice> spacemice = device::find_spacemice(*hid);
    for (const device::FoundDevice& f : spacemice)
        listed.push_back({f.capabilities, f.accessible, f.accessible ? "accessible" : f.reason, &f});

    if (args.json) {
        nlohmann::json all = nlohmann::json::array();
        for (const Listed& l : listed) {
            const device::Capabilities& c = l.caps;
            nlohmann::json j = {{"name", c.name},
                                {"driver", c.driver},
                                {"address", c.address},
                                {"control", control_name(c.control)},
                                {"degrees_of_freedom", c.degrees_of_freedom},
                                {"buttons", c.buttons},
                                {"force_feedback", c.has_force()},
                                {"max_force_N", c.max_force_N},
                                {"report_rate_hz", c.report_rate_hz},
                                {"available", l.available},
                                {"status", l.status}};
            if (l.hid != nullptr) {
                j["vendor_id"] = hex4(l.hid->hid.vendor_id);
                j["product_id"] = hex4(l.hid->hid.product_id);
                j["serial"] = l.hid->hid.serial;
                j["accessible"] = l.hid->accessible;
            }
            if (l.arm != nullptr) j["library_found"] = l.arm->library_found;
            if (c.has_force()) {
                j["max_stiffness_N_per_mm"] = c.max_stiffness_N_per_mm;
                j["workspace_mm"] = {c.workspace_mm.x(), c.workspace_mm.y(), c.workspace_mm.z()};
            }
            all.push_back(std::move(j));
        }
        std::printf("%s\n", all.dump(2).c_str());
        return kExitOk;
    }

    std::printf("devices echosim can drive:\n");
    for (const Listed& l : listed) {
        const device::Capabilities& c = l.caps;
        std::printf("  %s (%s): %s\n", c.name.c_str(), c.driver.c_str(), l.status.c_str());
        std::printf("      control %s, %d DOF, %d buttons, force: %s", control_name(c.control), c.degrees_of_freedom, c.buttons,
                    force_text(c).c_str());
        if (c.report_rate_hz > 0) std::printf(", reports at ~%.0f Hz", c.report_rate_hz);
        std::printf(", address: %s\n", c.address.c_str());
    }
    if (spacemice.empty()) std::printf("  no 3Dconnexion device found (vendor 046d/256f)\n");
    return kExitOk;
}

}  // namespace echosim::app

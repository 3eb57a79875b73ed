#include "device/hid_devices.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>

namespace echosim::device {
namespace {

struct ModelRow {
    std::uint16_t product_id;
    SpaceMouseModel model;
};

// Names as 3Dconnexion sells them. Button counts only where we are sure of them; the rest say 2
// (every model has at least the two side buttons) rather than guess.
constexpr ModelRow kModels[] = {
    {0xc603, {"SpaceMouse Plus XT", 2}},
    {0xc605, {"CadMan", 2}},
    {0xc606, {"SpaceMouse Classic", 2}},
    {0xc621, {"SpaceBall 5000", 2}},
    {0xc623, {"SpaceTraveler", 2}},
    {0xc625, {"SpacePilot", 2}},
    {0xc626, {"SpaceNavigator", 2}},
    {0xc627, {"SpaceExplorer", 15}},
    {0xc628, {"SpaceNavigator for Notebooks", 2}},
    {0xc629, {"SpacePilot Pro", 2}},
    {0xc62b, {"SpaceMouse Pro", 15}},
    {0xc62e, {"SpaceMouse Wireless (cable)", 2}},
    {0xc62f, {"SpaceMouse Wireless (receiver)", 2}},
    {0xc631, {"SpaceMouse Pro Wireless (cable)", 15}},
    {0xc632, {"SpaceMouse Pro Wireless (receiver)", 15}},
    {0xc633, {"SpaceMouse Enterprise", 31}},
    {0xc635, {"SpaceMouse Compact", 2}},
    {0xc636, {"SpaceMouse Module", 2}},
    {0xc640, {"NuLOOQ", 2}},
};

// An approximation: the family reports at about this rate while the cap moves, and not at all
// while it rests (the driver integrates between reports, so nothing depends on it).
constexpr double kReportRateHz = 60;

std::string hex4(std::uint16_t v)
{
    char s[8];
    std::snprintf(s, sizeof s, "%04x", unsigned(v));
    return s;
}

std::string name_of(const HidDeviceInfo& d)
{
    if (!d.product.empty())
        return d.product.find("3Dconnexion") == std::string::npos ? "3Dconnexion " + d.product : d.product;
    if (const SpaceMouseModel m = spacemouse_model(d.product_id); m.name != nullptr) return std::string("3Dconnexion ") + m.name;
    return "3Dconnexion device " + hex4(d.vendor_id) + ":" + hex4(d.product_id);
}

}  // namespace

Capabilities spacemouse_family_capabilities()
{
    Capabilities c;
    c.name = "3Dconnexion SpaceMouse";
    c.driver = "hidapi";
    c.address = "none yet: looking for vendor 046d/256f";
    c.control = Control::surface;
    c.degrees_of_freedom = 6;
    c.buttons = 2;
    c.report_rate_hz = kReportRateHz;
    return c;
}

bool is_spacemouse(std::uint16_t vendor_id, std::uint16_t product_id)
{
    if (vendor_id == kThreeDconnexionVendorId) return true;
    if (vendor_id != kLogitechVendorId) return false;
    return std::any_of(std::begin(kModels), std::end(kModels), [&](const ModelRow& r) { return r.product_id == product_id; });
}

SpaceMouseModel spacemouse_model(std::uint16_t product_id)
{
    for (const ModelRow& r : kModels)
        if (r.product_id == product_id) return r.model;
    return {nullptr, 2};
}

bool is_access_denied(const HidOpenResult& error)
{
    return error.error_code == EACCES || error.error_code == EPERM || error.error.find("Permission denied") != std::string::npos;
}

std::string access_denied_message(const std::string& path)
{
    return "the hidraw node " + path + " is not readable by this user; install the udev rule " + kUdevRuleFile +
           " (from the echosim source folder: sudo cp " + kUdevRuleFile +
           " /etc/udev/rules.d/ && sudo udevadm control --reload-rules && sudo udevadm trigger), then unplug the device and plug it back in";
}

std::vector<FoundDevice> find_spacemice(HidBackend& backend, bool check_access)
{
    std::vector<FoundDevice> found;
    for (HidDeviceInfo& d : backend.enumerate()) {
        if (!is_spacemouse(d.vendor_id, d.product_id)) continue;
        // hidapi lists a node once per top-level usage it declares; we open nodes, so one is enough
        if (std::any_of(found.begin(), found.end(), [&](const FoundDevice& f) { return f.hid.path == d.path; })) continue;
        FoundDevice f;
        f.capabilities = spacemouse_family_capabilities();
        f.capabilities.name = name_of(d);
        f.capabilities.address = d.path;
        f.capabilities.buttons = spacemouse_model(d.product_id).buttons;
        f.hid = std::move(d);
        if (check_access) {
            f.access_checked = true;
            const HidOpenResult r = backend.open(f.hid.path);
            f.accessible = r.handle != nullptr;
            if (f.accessible)
                backend.close(r.handle);
            else
                f.reason = is_access_denied(r) ? access_denied_message(f.hid.path) : "cannot open " + f.hid.path + ": " + r.error;
        }
        found.push_back(std::move(f));
    }
    return found;
}

}  // namespace echosim::device

// Which HID devices are SpaceMice, what they are called and whether this user may open them.
#include <cerrno>

#include <gtest/gtest.h>

#include "device/fake_hid_backend.hpp"
#include "device/hid_devices.hpp"

namespace echosim::device {
namespace {

using test::FakeHidBackend;

FakeHidBackend::Node node(const char* path, std::uint16_t vendor, std::uint16_t product, const char* name, bool denied = false)
{
    FakeHidBackend::Node n;
    n.info = {path, vendor, product, name, "S"};
    n.denied = denied;
    return n;
}

TEST(HidDevices, FindsTheSpaceMiceAndOnlyThem)
{
    FakeHidBackend fake({
        node("/dev/hidraw0", 0x046d, 0xc52b, "USB Receiver"),             // Logitech's own: not ours
        node("/dev/hidraw1", 0x046d, 0xc626, ""),                         // SpaceNavigator, no product string
        node("/dev/hidraw2", 0x256f, 0xc62b, "SpaceMouse Pro", true),      // not readable
        node("/dev/hidraw2", 0x256f, 0xc62b, "SpaceMouse Pro", true),      // the same node's second usage
        node("/dev/hidraw3", 0x256f, 0xc6ff, ""),                         // a 3Dconnexion product we do not know
        node("/dev/hidraw4", 0x1234, 0xc626, "SpaceNavigator"),           // the right product id, another vendor
        node("/dev/hidraw5", 0x256f, 0xc635, "3Dconnexion SpaceMouse Compact"),
    });

    const std::vector<FoundDevice> found = find_spacemice(fake);
    ASSERT_EQ(found.size(), 4u);
    EXPECT_EQ(found[0].capabilities.name, "3Dconnexion SpaceNavigator");
    EXPECT_EQ(found[0].capabilities.address, "/dev/hidraw1");
    EXPECT_EQ(found[0].capabilities.buttons, 2);
    EXPECT_EQ(found[1].capabilities.name, "3Dconnexion SpaceMouse Pro");
    EXPECT_EQ(found[1].capabilities.buttons, 15);
    EXPECT_EQ(found[2].capabilities.name, "3Dconnexion device 256f:c6ff");
    EXPECT_EQ(found[2].capabilities.buttons, 2);
    EXPECT_EQ(found[3].capabilities.name, "3Dconnexion SpaceMouse Compact");
    for (const FoundDevice& f : found) {
        EXPECT_EQ(f.capabilities.driver, "hidapi");
        EXPECT_EQ(f.capabilities.control, Control::surface);
        EXPECT_EQ(f.capabilities.degrees_of_freedom, 6);
        EXPECT_FALSE(f.capabilities.has_force());
        EXPECT_GT(f.capabilities.report_rate_hz, 0.0);
        EXPECT_TRUE(f.access_checked);
    }
    EXPECT_TRUE(found[0].accessible);
    EXPECT_TRUE(found[0].reason.empty());
    EXPECT_FALSE(found[1].accessible);
    EXPECT_EQ(found[1].reason, access_denied_message("/dev/hidraw2"));
    EXPECT_NE(found[1].reason.find(kUdevRuleFile), std::string::npos);
    EXPECT_EQ(fake.open_handles(), 0);  // what it opened to check, it closed

    const int attempts = fake.open_attempts();
    const std::vector<FoundDevice> unchecked = find_spacemice(fake, false);
    EXPECT_EQ(unchecked.size(), 4u);
    EXPECT_FALSE(unchecked[0].access_checked);
    EXPECT_EQ(fake.open_attempts(), attempts);
}

TEST(HidDevices, VendorsAndProducts)
{
    EXPECT_TRUE(is_spacemouse(0x046d, 0xc626));
    EXPECT_TRUE(is_spacemouse(0x046d, 0xc603));
    EXPECT_TRUE(is_spacemouse(0x046d, 0xc640));
    EXPECT_FALSE(is_spacemouse(0x046d, 0xc52b));
    EXPECT_FALSE(is_spacemouse(0x046d, 0xc62a));
    EXPECT_TRUE(is_spacemouse(0x256f, 0x0001));
    EXPECT_FALSE(is_spacemouse(0x1234, 0xc626));
    EXPECT_EQ(spacemouse_model(0xc633).buttons, 31);
    EXPECT_EQ(spacemouse_model(0x0001).name, nullptr);
    EXPECT_EQ(spacemouse_model(0x0001).buttons, 2);
}

TEST(HidDevices, AccessDenied)
{
    EXPECT_TRUE(is_access_denied({nullptr, EACCES, "whatever"}));
    EXPECT_TRUE(is_access_denied({nullptr, EPERM, ""}));
    EXPECT_TRUE(is_access_denied({nullptr, 0, "Failed to open a device with path '/dev/hidraw3': Permission denied"}));
    EXPECT_FALSE(is_access_denied({nullptr, ENOENT, "Failed to open a device with path '/dev/hidraw3': No such file or directory"}));
    EXPECT_EQ(access_denied_message("/dev/hidraw3"),
              "the hidraw node /dev/hidraw3 is not readable by this user; install the udev rule "
              "device/udev/70-echosim-spacemouse.rules (from the echosim source folder: sudo cp "
              "device/udev/70-echosim-spacemouse.rules /etc/udev/rules.d/ && sudo udevadm control --reload-rules && "
              "sudo udevadm trigger), then unplug the device and plug it back in");
}

// The real backend on this machine: whatever is plugged in, finding devices neither fails nor
// leaves anything open, and hid_init/hid_exit pair up across backends made one after another.
TEST(HidDevices, HidapiBackendEnumerates)
{
    for (int i = 0; i < 3; ++i) {
        const std::shared_ptr<HidBackend> a = hidapi_backend();
        const std::shared_ptr<HidBackend> b = hidapi_backend();
        const std::vector<FoundDevice> found = find_spacemice(*a);
        for (const FoundDevice& f : found) EXPECT_TRUE(f.accessible || !f.reason.empty());
        EXPECT_EQ(find_spacemice(*b, false).size(), found.size());
        EXPECT_EQ(b->open("/dev/echosim-no-such-node").handle, nullptr);
    }
}

}  // namespace
}  // namespace echosim::device

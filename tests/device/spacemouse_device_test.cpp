// The SpaceMouse driver over a fake HID backend: it connects, follows the cap, loses the device and
// finds it again, and says once what to do about a node it may not read. No timing is asserted:
// each wait polls up to a generous deadline for what must eventually happen.
#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "device/fake_hid_backend.hpp"
#include "device/spacemouse_device.hpp"

namespace echosim::device {
namespace {

using namespace std::chrono_literals;
using test::FakeHidBackend;

constexpr auto kDeadline = 5s;
const char* const kCompactName = "3Dconnexion SpaceMouse Compact";

std::shared_ptr<FakeHidBackend> one_compact(bool present = true, bool denied = false)
{
    FakeHidBackend::Node n;
    n.info = {"/dev/hidraw7", kThreeDconnexionVendorId, 0xc635, "SpaceMouse Compact", "SN0001"};
    n.present = present;
    n.denied = denied;
    return std::make_shared<FakeHidBackend>(std::vector{n});
}

// The first event of `kind` to arrive after the call (everything that arrives goes into `log`).
std::optional<DeviceEvent> wait_event(Device& d, DeviceEvent::Kind kind, std::vector<DeviceEvent>& log,
                                      std::chrono::seconds deadline = kDeadline)
{
    const std::size_t from = log.size();
    const auto until = std::chrono::steady_clock::now() + deadline;
    for (;;) {
        d.events(log);
        for (std::size_t i = from; i < log.size(); ++i)
            if (log[i].kind == kind) return log[i];
        if (std::chrono::steady_clock::now() > until) return std::nullopt;
        std::this_thread::sleep_for(2ms);
    }
}

// Reads as the haptic thread would until a sample satisfies `ok`.
std::optional<DeviceSample> wait_sample(Device& d, const std::function<bool(const DeviceSample&)>& ok)
{
    const auto until = std::chrono::steady_clock::now() + kDeadline;
    DeviceSample s;
    for (;;) {
        d.read(0.0, s);
        if (ok(s)) return s;
        if (std::chrono::steady_clock::now() > until) return std::nullopt;
        std::this_thread::sleep_for(1ms);
    }
}

int count(const std::vector<DeviceEvent>& log, DeviceEvent::Kind kind)
{
    return int(std::count_if(log.begin(), log.end(), [&](const DeviceEvent& e) { return e.kind == kind; }));
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

TEST(SpaceMouseDevice, DescribesTheDevicePresent)
{
    SpaceMouseDevice dev(one_compact());
    const Capabilities& c = dev.capabilities();
    EXPECT_EQ(c.name, kCompactName);
    EXPECT_EQ(c.driver, "hidapi");
    EXPECT_EQ(c.address, "/dev/hidraw7");
    EXPECT_EQ(c.control, Control::surface);
    EXPECT_EQ(c.degrees_of_freedom, 6);
    EXPECT_EQ(c.buttons, 2);
    EXPECT_EQ(c.max_force_N, 0.0);
    EXPECT_FALSE(c.has_force());
}

TEST(SpaceMouseDevice, FollowsTheCapLosesTheDeviceAndFindsItAgain)
{
    const auto fake = one_compact();
    SpaceMouseDevice dev(fake);
    std::vector<DeviceEvent> log;

    const auto hello = wait_event(dev, DeviceEvent::Kind::connected, log);
    ASSERT_TRUE(hello);
    EXPECT_EQ(hello->device, kCompactName);
    EXPECT_TRUE(contains(hello->message, "/dev/hidraw7")) << hello->message;
    auto s = wait_sample(dev, [](const DeviceSample& x) { return x.connected; });
    ASSERT_TRUE(s);
    EXPECT_EQ(s->control, Control::surface);
    EXPECT_EQ(s->surface.u, 0.5);
    EXPECT_EQ(s->surface.v, 0.5);
    EXPECT_EQ(s->surface.press_mm, 0.0);

    // pushed all the way in (the 13-byte form, tz = 0x015e = 350): 20 mm, and nothing slides
    fake->send({0x01, 0x00, 0x00, 0x00, 0x00, 0x5e, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
    s = wait_sample(dev, [](const DeviceSample& x) { return x.surface.press_mm > 0; });
    ASSERT_TRUE(s);
    EXPECT_DOUBLE_EQ(s->surface.press_mm, 20.0);
    EXPECT_EQ(s->surface.u, 0.5);
    EXPECT_EQ(s->surface.v, 0.5);

    // slid around the thigh (tx = 350) while pressed, then stopped; the button report after the stop
    // tells us when the stop has been read
    fake->send({0x01, 0x5e, 0x01, 0x00, 0x00, 0x5e, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
    ASSERT_TRUE(wait_sample(dev, [](const DeviceSample& x) { return x.surface.v > 0.5; }));
    fake->send({0x01, 0x00, 0x00, 0x00, 0x00, 0x5e, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
    fake->send({0x03, 0x02});
    s = wait_sample(dev, [](const DeviceSample& x) { return x.buttons == 2u; });
    ASSERT_TRUE(s);
    const double v_stopped = s->surface.v;
    EXPECT_GT(v_stopped, 0.5);
    EXPECT_LE(v_stopped, 1.0);
    EXPECT_EQ(s->surface.u, 0.5);
    EXPECT_DOUBLE_EQ(s->surface.press_mm, 20.0);
    const std::uint64_t sequence = s->sequence;

    // unplugged: said, and the probe lifts off where it was
    fake->unplug(0);
    const auto gone = wait_event(dev, DeviceEvent::Kind::disconnected, log);
    ASSERT_TRUE(gone);
    EXPECT_EQ(gone->device, kCompactName);
    EXPECT_EQ(gone->message, std::string("read failed: ") + FakeHidBackend::kReadError + "; looking for it again");
    s = wait_sample(dev, [](const DeviceSample& x) { return !x.connected; });
    ASSERT_TRUE(s);
    EXPECT_EQ(s->surface.press_mm, 0.0);
    EXPECT_EQ(s->surface.v, v_stopped);
    EXPECT_EQ(s->surface.u, 0.5);
    EXPECT_EQ(s->buttons, 0u);
    EXPECT_GT(s->sequence, sequence);
    DeviceSample again;
    EXPECT_FALSE(dev.read(0.0, again));
    EXPECT_EQ(fake->open_handles(), 0);

    // back: from where it was, not pressed until the cap is pushed again
    fake->plug(0);
    ASSERT_TRUE(wait_event(dev, DeviceEvent::Kind::connected, log));
    s = wait_sample(dev, [](const DeviceSample& x) { return x.connected; });
    ASSERT_TRUE(s);
    EXPECT_EQ(s->surface.v, v_stopped);
    EXPECT_EQ(s->surface.u, 0.5);
    EXPECT_EQ(s->surface.press_mm, 0.0);
    // tz = 0x00af = 175: 135 of the 310 counts past the dead zone
    fake->send({0x01, 0x00, 0x00, 0x00, 0x00, 0xaf, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
    s = wait_sample(dev, [](const DeviceSample& x) { return x.surface.press_mm > 0; });
    ASSERT_TRUE(s);
    EXPECT_DOUBLE_EQ(s->surface.press_mm, 135.0 / 310.0 * 20.0);
    EXPECT_TRUE(s->connected);
    EXPECT_EQ(count(log, DeviceEvent::Kind::access_denied), 0);
}

TEST(SpaceMouseDevice, AccessDeniedIsSaidOnceWithTheRuleThatFixesIt)
{
    const auto fake = one_compact(true, true);
    SpaceMouseDevice dev(fake);
    std::vector<DeviceEvent> log;

    // several rounds of looking, each refused
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (fake->open_attempts() < 3 && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(5ms);
    ASSERT_GE(fake->open_attempts(), 3);
    dev.events(log);
    ASSERT_EQ(count(log, DeviceEvent::Kind::access_denied), 1);
    const DeviceEvent& denied = *std::find_if(log.begin(), log.end(), [](const DeviceEvent& e) { return e.kind == DeviceEvent::Kind::access_denied; });
    EXPECT_EQ(denied.device, kCompactName);
    EXPECT_TRUE(contains(denied.message, "the hidraw node /dev/hidraw7 is not readable by this user")) << denied.message;
    EXPECT_TRUE(contains(denied.message, "device/udev/70-echosim-spacemouse.rules")) << denied.message;
    EXPECT_TRUE(contains(denied.message,
                         "sudo cp device/udev/70-echosim-spacemouse.rules /etc/udev/rules.d/ && sudo udevadm control --reload-rules && "
                         "sudo udevadm trigger"))
        << denied.message;
    EXPECT_EQ(count(log, DeviceEvent::Kind::connected), 0);
    DeviceSample s;
    EXPECT_FALSE(dev.read(0.0, s));

    // the rule installed: it connects, and the refusal is not said again
    fake->allow(0);
    ASSERT_TRUE(wait_event(dev, DeviceEvent::Kind::connected, log));
    EXPECT_TRUE(wait_sample(dev, [](const DeviceSample& x) { return x.connected; }));
    EXPECT_EQ(count(log, DeviceEvent::Kind::access_denied), 1);
}

TEST(SpaceMouseDevice, WithoutADeviceKeepsLookingFromTheStart)
{
    const auto fake = one_compact(false);
    SurfacePlacement start;
    start.u = 0.3;
    start.v = 0.7;
    start.press_mm = 5;  // no hand on the cap yet: not pressed
    SpaceMouseDevice dev(fake, {}, start);
    EXPECT_EQ(dev.capabilities().name, "3Dconnexion SpaceMouse");
    EXPECT_EQ(dev.capabilities().degrees_of_freedom, 6);

    std::vector<DeviceEvent> log;
    const auto note = wait_event(dev, DeviceEvent::Kind::note, log);
    ASSERT_TRUE(note);
    EXPECT_TRUE(contains(note->message, "no 3Dconnexion device found (vendor 046d/256f)")) << note->message;
    DeviceSample s;
    EXPECT_FALSE(dev.read(0.0, s));
    EXPECT_EQ(s.surface.u, 0.3);
    EXPECT_EQ(s.surface.v, 0.7);
    EXPECT_EQ(s.surface.press_mm, 0.0);

    fake->plug(0);
    ASSERT_TRUE(wait_event(dev, DeviceEvent::Kind::connected, log));
    const auto c = wait_sample(dev, [](const DeviceSample& x) { return x.connected; });
    ASSERT_TRUE(c);
    EXPECT_EQ(c->surface.u, 0.3);
    EXPECT_EQ(c->surface.v, 0.7);
    EXPECT_EQ(count(log, DeviceEvent::Kind::note), 1);
}

TEST(SpaceMouseDevice, ReportsItDoesNotReadAreNotedOnce)
{
    const auto fake = one_compact();
    SpaceMouseDevice dev(fake);
    std::vector<DeviceEvent> log;
    ASSERT_TRUE(wait_event(dev, DeviceEvent::Kind::connected, log));
    fake->send({0x17, 0x64});  // a wireless model's battery level
    fake->send({0x17, 0x63});
    fake->send({0x01, 0x02});  // truncated: not a note, just not used
    fake->send({0x03, 0x01});
    ASSERT_TRUE(wait_sample(dev, [](const DeviceSample& x) { return x.buttons == 1u; }));
    dev.events(log);
    ASSERT_EQ(count(log, DeviceEvent::Kind::note), 1);
    const DeviceEvent& note = *std::find_if(log.begin(), log.end(), [](const DeviceEvent& e) { return e.kind == DeviceEvent::Kind::note; });
    EXPECT_TRUE(contains(note.message, "0x17")) << note.message;
}

}  // namespace
}  // namespace echosim::device

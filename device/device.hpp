// The one interface every input and haptic device sits behind (DESIGN.md §1, "devices"; after
// CHAI3D's generic haptic device): pose and buttons in, force out, capabilities in units, connect and
// disconnect events. The haptic loop (engine/haptics) is its user; it turns a sample into the probe's
// pose (haptics/probe_mapping) and a force into the device's frame.
//
// Threads. A device is used from two threads, each through its own calls:
//   - the haptic thread (or, lock-step, the headless driver standing in for it): read() and
//     write_force(). They never block, never allocate and never throw: a driver whose I/O can block
//     or allocate (HID, which enumerates and opens devices) does it on a thread of its own and hands
//     the latest sample over through a lock-free triple buffer (core/triple_buffer.hpp); an arm's
//     servo API, which is made for a 1 kHz loop, is called from read() and write_force() directly.
//   - the session's driver thread (the window's main thread, a headless command): events(), and
//     whatever feeds a device from there (the window's mouse and keyboard).
// capabilities() is fixed once the device is made and may be read from any thread.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace echosim::device {

// How a device's sample places the probe.
enum class Control {
    surface,    // over the skin: where on the exam patch, tilted, pressed (mouse and keyboard, SpaceMouse)
    workspace,  // a handle's pose in the device's own workspace, mapped onto the patient (force-feedback arms)
    world,      // the probe's pose in world LPS millimetres as it is (a scripted trajectory)
};
const char* to_string(Control c);

// The probe placed over the skin: the exam patch's (u, v) in [0,1]^2 (u along the thigh, from
// superior to inferior; v around it, from medial towards anterior), the probe tilted from the skin's
// normal, and pressed along its tilted beam.
struct SurfacePlacement {
    double u = 0.5, v = 0.5;
    double fan_rad = 0;   // about the probe's lateral axis (the array): sweeps the image plane [rad]
    double rock_rad = 0;  // about the elevational axis: heel-toe, in the image plane [rad]
    double press_mm = 0;  // along the beam [mm], >= 0
    double twist_rad = 0; // about the beam, before the tilts: 0 transverse, pi/2 longitudinal [rad]

    static constexpr double kMaxTiltRad = 0.5236;  // 30 degrees either way
    static constexpr double kMaxPressMm = 25.0;
};

// Where a surface placement may go, in the exam patch's (u, v): the patch itself by default; the
// whole exam limb's course when the session's window follows the probe (u and v then run past
// [0, 1] along and around the limb in the home patch's own frame: haptics::exam_limb_surface).
struct SurfaceLimits {
    double u_lo = 0, u_hi = 1, v_lo = 0, v_hi = 1;
};

struct DeviceSample {
    std::uint64_t sequence = 0;  // counts the device's reports; unchanged: nothing new since the last
    bool connected = false;      // false: the device is gone; the rest is its last report
    Control control = Control::surface;
    SurfacePlacement surface;                                   // Control::surface
    Eigen::Vector3d position = Eigen::Vector3d::Zero();         // workspace [mm] or world [mm]
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // workspace or world
    std::uint32_t buttons = 0;   // bit i: button i held
};

// What a device can do, in units (CHAI3D's specification, at our scale).
struct Capabilities {
    std::string name;     // "3Dconnexion SpaceMouse Compact"
    std::string driver;   // "hidapi", "mouse and keyboard", "scripted", "null"
    std::string address;  // where it is: a hidraw path, a file, the window
    Control control = Control::surface;
    int degrees_of_freedom = 0;
    int buttons = 0;
    double report_rate_hz = 0;  // how often it reports (0: every read)
    // Control::workspace: the handle's reach, a box centred on the workspace origin [mm]
    Eigen::Vector3d workspace_mm = Eigen::Vector3d::Zero();
    // force feedback; all 0 for a device without it
    double max_force_N = 0;               // the largest force it renders continuously
    double max_stiffness_N_per_mm = 0;    // the stiffest contact it renders stably in a 1 kHz loop
    double max_damping_N_s_per_mm = 0;
    bool has_force() const { return max_force_N > 0; }
};

struct DeviceEvent {
    enum class Kind {
        connected,
        disconnected,   // unplugged, or a read failed: the driver keeps looking for it
        access_denied,  // present but not ours to open (the message says how to fix it)
        note,           // anything else a user should know (a report we do not understand, once)
    };
    Kind kind = Kind::note;
    std::string device;   // the device's name
    std::string message;  // a sentence for the log and the window
};
const char* to_string(DeviceEvent::Kind k);

// How long an arm holds the force it was last sent [s]: a loop that stopped or stalled for 20 of its
// ticks no longer pushes on the user's hand.
inline constexpr double kForceHoldS = 0.02;

class Device {
public:
    virtual ~Device() = default;

    virtual const Capabilities& capabilities() const = 0;

    // Haptic thread. The latest sample at time `t_s` (the loop's clock: seconds since it started,
    // or simulated time in lock-step); false while the device is not connected (`out` then keeps its
    // last pose, marked not connected).
    virtual bool read(double t_s, DeviceSample& out) noexcept = 0;
    // Haptic thread. The force on the user's hand, in the device's frame (workspace axes) [N],
    // already within capabilities().max_force_N. A device without force feedback ignores it. An
    // arm's driver cuts it to its limit again (a NaN sends nothing), sends it from its next servo
    // tick on (so a zero sent on stop takes effect within a millisecond), replaces a force not
    // renewed for kForceHoldS by zero, and sends zero force when destroyed.
    virtual void write_force(const Eigen::Vector3d& force_N) noexcept = 0;

    // Driver thread. Connection changes and notes since the last call, oldest first (appended).
    virtual void events(std::vector<DeviceEvent>& out) = 0;
};

}  // namespace echosim::device

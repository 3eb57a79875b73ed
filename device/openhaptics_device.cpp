#include "device/openhaptics_device.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <stdexcept>

namespace echosim::device {

using namespace hd;

namespace {

std::int64_t steady_ns()
{
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

constexpr const char* kWhatToCheck =
    "is the arm plugged in, paired with Touch_Setup (or Touch_AdvancedConfig) and not held by another program?";

// The family's figures (device/README.md), for an arm not found: what `echosim devices` describes.
Capabilities touch_family()
{
    Capabilities c;
    c.name = "3D Systems Touch / Phantom";
    c.driver = "OpenHaptics HD";
    c.address = "-";
    c.control = Control::workspace;
    c.degrees_of_freedom = 6;
    c.buttons = 2;
    c.report_rate_hz = 1000;
    c.workspace_mm = Eigen::Vector3d(160, 120, 70);
    c.max_force_N = 0.88;
    c.max_stiffness_N_per_mm = 1.26;
    c.max_damping_N_s_per_mm = 0.00126;  // the stiffness times one 1 kHz period (below)
    return c;
}

// a device or communication fault: the arm is gone until a frame goes through again
bool is_fault(HDerror code) { return code >= HD_DEVICE_FAULT && code < HD_ILLEGAL_BEGIN; }

// every error hdGetError has queued, oldest first: the first fault among them (a force error queued
// before it must not hide it), else the first error; the rest dropped
HDErrorInfo pop_errors(const HdApi& api)
{
    HDErrorInfo first{HD_SUCCESS, 0, HD_INVALID_HANDLE};
    for (int i = 0; i < 16; ++i) {
        const HDErrorInfo e = api.hdGetError();
        if (e.errorCode == HD_SUCCESS) break;
        if (first.errorCode == HD_SUCCESS || (is_fault(e.errorCode) && !is_fault(first.errorCode))) first = e;
    }
    return first;
}

[[noreturn]] void fail(const HdApi& api, const std::string& call, const HDErrorInfo& e)
{
    throw std::runtime_error("OpenHaptics (" + api.path + "): " + call + ": " + describe(api, e) + "; " + kWhatToCheck);
}

void check(const HdApi& api, const std::string& call)
{
    if (const HDErrorInfo e = pop_errors(api); e.errorCode != HD_SUCCESS) fail(api, call, e);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

std::string text(HDstring s) { return s != nullptr ? std::string(s) : std::string(); }

struct ArmReport {
    Capabilities caps;
    Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
};

// What the arm `hhd` (current) says of itself, checked: a limit it cannot have refuses the arm, since
// the force and stiffness the loop renders are cut to these.
ArmReport query_arm(const HdApi& api, HHD hhd)
{
    ArmReport r;
    Capabilities& c = r.caps;
    c = touch_family();
    const std::string model = text(api.hdGetString(HD_DEVICE_MODEL_TYPE));
    const std::string serial = text(api.hdGetString(HD_DEVICE_SERIAL_NUMBER));
    check(api, "hdGetString(HD_DEVICE_MODEL_TYPE)");
    c.name = model.empty() ? "OpenHaptics arm" : "3D Systems " + model;
    c.address = "HD device " + std::to_string(hhd) + (serial.empty() ? "" : ", serial " + serial) + ", through " + api.path;

    double box[6] = {};
    api.hdGetDoublev(HD_USABLE_WORKSPACE_DIMENSIONS, box);
    check(api, "hdGetDoublev(HD_USABLE_WORKSPACE_DIMENSIONS)");
    const Eigen::Vector3d lo(box[0], box[1], box[2]), hi(box[3], box[4], box[5]);
    const Eigen::Vector3d size = hi - lo;
    if (!(positive(size.x()) && positive(size.y()) && positive(size.z())))
        throw std::runtime_error("OpenHaptics (" + api.path + "): " + c.name + " reports a usable workspace of " + std::to_string(size.x()) +
                                 " x " + std::to_string(size.y()) + " x " + std::to_string(size.z()) + " mm (HD_USABLE_WORKSPACE_DIMENSIONS); recalibrate it");
    c.workspace_mm = size;
    r.centre_mm = 0.5 * (lo + hi);

    // the force: the continuous figure where the arm has one (device/README.md), never above its peak
    double peak = 0, continuous = 0;
    api.hdGetDoublev(HD_NOMINAL_MAX_FORCE, &peak);
    check(api, "hdGetDoublev(HD_NOMINAL_MAX_FORCE)");
    if (!positive(peak))
        throw std::runtime_error("OpenHaptics (" + api.path + "): " + c.name + " reports a nominal maximum force of " + std::to_string(peak) +
                                 " N (HD_NOMINAL_MAX_FORCE): refused, its force cannot be limited");
    api.hdGetDoublev(HD_NOMINAL_MAX_CONTINUOUS_FORCE, &continuous);
    const bool has_continuous = pop_errors(api).errorCode == HD_SUCCESS && positive(continuous);
    c.max_force_N = has_continuous ? std::min(continuous, peak) : peak;

    double stiffness = 0, damping = 0;
    api.hdGetDoublev(HD_NOMINAL_MAX_STIFFNESS, &stiffness);
    check(api, "hdGetDoublev(HD_NOMINAL_MAX_STIFFNESS)");
    if (!positive(stiffness))
        throw std::runtime_error("OpenHaptics (" + api.path + "): " + c.name + " reports a nominal maximum stiffness of " +
                                 std::to_string(stiffness) + " N/mm (HD_NOMINAL_MAX_STIFFNESS): refused, a contact could not be rendered stably");
    c.max_stiffness_N_per_mm = stiffness;
    api.hdGetDoublev(HD_NOMINAL_MAX_DAMPING, &damping);
    // without a figure: the stiffness times one period, a damper that at 1 kHz adds no more than the
    // spring it sits beside
    c.max_damping_N_s_per_mm = pop_errors(api).errorCode == HD_SUCCESS && positive(damping) ? damping : stiffness * 1e-3;

    HDint dof = 0, rate = 0;
    api.hdGetIntegerv(HD_INPUT_DOF, &dof);
    if (pop_errors(api).errorCode == HD_SUCCESS && dof > 0) c.degrees_of_freedom = dof;
    api.hdGetIntegerv(HD_UPDATE_RATE, &rate);
    if (pop_errors(api).errorCode == HD_SUCCESS && rate > 0) c.report_rate_hz = rate;
    return r;
}

// the handle's pose from HD_CURRENT_TRANSFORM (column-major, OpenGL's layout), about the workspace centre
void pose_from(const double m[16], const Eigen::Vector3d& centre, DeviceSample& s)
{
    Eigen::Matrix3d r;
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) r(row, col) = m[col * 4 + row];
    const Eigen::Vector3d t(m[12], m[13], m[14]);
    if (!t.allFinite() || !r.allFinite()) return;  // keep the last pose
    s.position = t - centre;
    // a transform a hair off orthonormal (the encoders' rounding) still gives its nearest rotation
    s.orientation = Eigen::Quaterniond(r).normalized();
}

DeviceSample resting_arm()
{
    DeviceSample s;
    s.control = Control::workspace;
    s.connected = false;  // until the servo's first frame
    return s;
}

}  // namespace

OpenHapticsDevice::OpenHapticsDevice(std::shared_ptr<const HdApi> api)
    : api_(std::move(api)), servo_sample_(resting_arm()), state_(resting_arm())
{
    if (!api_) throw std::invalid_argument("OpenHapticsDevice: no HD library");
    const HdApi& hd = *api_;
    pop_errors(hd);  // nothing of an earlier user's is ours
    hhd_ = hd.hdInitDevice(HD_DEFAULT_DEVICE);
    if (const HDErrorInfo e = pop_errors(hd); e.errorCode != HD_SUCCESS || hhd_ == HD_INVALID_HANDLE) {
        if (hhd_ != HD_INVALID_HANDLE) hd.hdDisableDevice(hhd_);
        fail(hd, "hdInitDevice(HD_DEFAULT_DEVICE)", e);
    }
    try {
        const ArmReport report = query_arm(hd, hhd_);
        caps_ = report.caps;
        centre_mm_ = report.centre_mm;
        hd.hdEnable(HD_FORCE_OUTPUT);
        check(hd, "hdEnable(HD_FORCE_OUTPUT)");
        callback_ = hd.hdScheduleAsynchronous(&OpenHapticsDevice::servo, this, HD_MAX_SCHEDULER_PRIORITY);
        check(hd, "hdScheduleAsynchronous");
        hd.hdStartScheduler();
        check(hd, "hdStartScheduler");
    } catch (...) {
        hd.hdStopScheduler();
        if (callback_ != 0) hd.hdUnschedule(callback_);
        hd.hdDisable(HD_FORCE_OUTPUT);
        hd.hdDisableDevice(hhd_);
        pop_errors(hd);
        throw;
    }
}

OpenHapticsDevice::~OpenHapticsDevice()
{
    const HdApi& hd = *api_;
    // zero force first, in a frame of the servo's own (hdScheduleSynchronous returns once it ran);
    // from then on the asynchronous callback sends zero too, until it is unscheduled
    stopping_.store(true, std::memory_order_release);
    hd.hdScheduleSynchronous(&OpenHapticsDevice::send_zero, this, HD_MAX_SCHEDULER_PRIORITY);
    hd.hdStopScheduler();
    hd.hdUnschedule(callback_);
    hd.hdDisable(HD_FORCE_OUTPUT);
    hd.hdDisableDevice(hhd_);
    pop_errors(hd);
}

HDCallbackCode OpenHapticsDevice::servo(void* self) noexcept { return static_cast<OpenHapticsDevice*>(self)->servo_frame(false); }

HDCallbackCode OpenHapticsDevice::send_zero(void* self) noexcept
{
    static_cast<OpenHapticsDevice*>(self)->servo_frame(true);
    return HD_CALLBACK_DONE;
}

HDCallbackCode OpenHapticsDevice::servo_frame(bool zero_only) noexcept
{
    const HdApi& hd = *api_;
    hd.hdBeginFrame(hhd_);
    double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    HDint buttons = 0;
    if (!zero_only) {
        hd.hdGetDoublev(HD_CURRENT_TRANSFORM, m);
        hd.hdGetIntegerv(HD_CURRENT_BUTTONS, &buttons);
    }
    // the force the loop asked for, unless it is stale, we are stopping, or the last frame failed
    // (the loop's force was worked out from a pose the arm no longer vouches for); cut to the limit
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    const bool was_faulted = !connected_.load(std::memory_order_relaxed);  // this thread is its one writer
    if (!zero_only && !was_faulted && !stopping_.load(std::memory_order_acquire)) {
        const Command& c = command_.read();
        if (c.stamp_ns != 0 && double(steady_ns() - c.stamp_ns) * 1e-9 <= kForceHoldS && c.force_N.allFinite()) {
            f = c.force_N;
            const double n = f.norm();
            if (n > caps_.max_force_N) f *= caps_.max_force_N / n;
        }
    }
    const double force[3] = {f.x(), f.y(), f.z()};
    hd.hdSetDoublev(HD_CURRENT_FORCE, force);
    hd.hdEndFrame(hhd_);

    const HDErrorInfo e = pop_errors(hd);
    if (zero_only) return HD_CALLBACK_DONE;
    // device and communication faults: the arm is gone until a frame goes through again; any other
    // error (a force error: motors too warm, a velocity or impulse over the arm's limit, which the
    // arm answers by cutting its force itself; a frame or scheduler error) is counted and said
    const bool fault = is_fault(e.errorCode);
    if (fault) {
        fault_internal_.store(e.internalErrorCode, std::memory_order_relaxed);
        fault_code_.store(e.errorCode, std::memory_order_relaxed);
    } else if (e.errorCode != HD_SUCCESS) {
        frame_error_code_.store(e.errorCode, std::memory_order_relaxed);
        frame_errors_.fetch_add(1, std::memory_order_relaxed);
    }
    connected_.store(!fault, std::memory_order_release);

    // a faulted frame's readings are not the handle's: the last pose stays, marked not connected
    DeviceSample& s = servo_sample_;
    if (!fault) pose_from(m, centre_mm_, s);
    s.sequence = ++sequence_;
    s.connected = !fault;
    s.buttons = fault ? 0u : std::uint32_t(buttons);
    state_.write_slot() = s;
    state_.publish();
    return HD_CALLBACK_CONTINUE;
}

bool OpenHapticsDevice::read(double, DeviceSample& out) noexcept
{
    out = state_.read();
    return out.connected;
}

void OpenHapticsDevice::write_force(const Eigen::Vector3d& force_N) noexcept
{
    Command& c = command_.write_slot();
    c.force_N = force_N;
    c.stamp_ns = steady_ns();
    command_.publish();
}

void OpenHapticsDevice::events(std::vector<DeviceEvent>& out)
{
    if (!announced_) {
        announced_ = true;
        char limits[160];
        std::snprintf(limits, sizeof limits, "%.0f x %.0f x %.0f mm, forces up to %.2f N, stiffness up to %.2f N/mm", caps_.workspace_mm.x(),
                      caps_.workspace_mm.y(), caps_.workspace_mm.z(), caps_.max_force_N, caps_.max_stiffness_N_per_mm);
        out.push_back({DeviceEvent::Kind::connected, caps_.name,
                       caps_.address + ": " + limits + "; move the handle down to press the probe into the skin"});
    }
    const bool now = connected_.load(std::memory_order_acquire);
    if (now != reported_connected_) {
        reported_connected_ = now;
        if (now) {
            out.push_back({DeviceEvent::Kind::connected, caps_.name, "the arm answers again"});
        } else {
            const HDErrorInfo e{fault_code_.load(std::memory_order_relaxed), fault_internal_.load(std::memory_order_relaxed), hhd_};
            out.push_back({DeviceEvent::Kind::disconnected, caps_.name,
                           "servo frame failed: " + describe(*api_, e) + "; no force is sent until it answers again; " + kWhatToCheck});
        }
    }
    if (const std::uint64_t n = frame_errors_.load(std::memory_order_relaxed); n != reported_frame_errors_) {
        const HDerror code = frame_error_code_.load(std::memory_order_relaxed);
        const bool force_error = code >= HD_WARM_MOTORS && code < HD_DEVICE_FAULT;
        out.push_back({DeviceEvent::Kind::note, caps_.name,
                       std::to_string(n - reported_frame_errors_) + " servo frame(s) reported an error, the last " + hd_error_name(code) +
                           (force_error ? ": the arm cut its force itself" : "")});
        reported_frame_errors_ = n;
    }
}

OpenHapticsProbe probe_openhaptics(const HdLoad& load)
{
    OpenHapticsProbe p;
    p.capabilities = touch_family();
    if (!load.api) {
        p.status = "OpenHaptics' libHD.so not found (" + load.error + "); " + kInstallHint;
        return p;
    }
    p.library_found = true;
    const HdApi& hd = *load.api;
    p.capabilities.address = load.api->path;
    pop_errors(hd);
    const HHD hhd = hd.hdInitDevice(HD_DEFAULT_DEVICE);
    if (const HDErrorInfo e = pop_errors(hd); e.errorCode != HD_SUCCESS || hhd == HD_INVALID_HANDLE) {
        if (hhd != HD_INVALID_HANDLE) hd.hdDisableDevice(hhd);
        p.status = "OpenHaptics found (" + hd.path + ") but no arm answers: hdInitDevice(HD_DEFAULT_DEVICE): " + describe(hd, e) + "; " +
                   kWhatToCheck;
        return p;
    }
    try {
        p.capabilities = query_arm(hd, hhd).caps;
        p.available = true;
        p.status = "ready (echosim run --device openhaptics)";
    } catch (const std::exception& e) {
        p.status = e.what();
    }
    hd.hdDisableDevice(hhd);
    pop_errors(hd);
    return p;
}

OpenHapticsProbe probe_openhaptics() { return probe_openhaptics(load_hd_library()); }

}  // namespace echosim::device

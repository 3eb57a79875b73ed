// A stand-in for OpenHaptics' libHD.so, built by the tests as a shared library of its own and loaded
// through the driver's own loader (dlopen/dlsym, device/openhaptics_api.cpp): it exports the hd*
// functions the driver binds, with the HD API's C signatures, plays one arm whose pose, buttons,
// limits and faults a test sets, and records what the driver did (fake_hd_control.hpp). Its servo
// runs only when a test asks (fake_hd_servo), in the test's thread, so every frame is deterministic.
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "device/openhaptics_api.hpp"

using namespace echosim::device::hd;

namespace {

struct Fake {
    std::recursive_mutex mutex;  // recursive: a synchronous callback calls back in
    std::deque<HDErrorInfo> errors;
    HDerror init_error = HD_SUCCESS;
    int init_internal = 0;
    HDerror fault = HD_SUCCESS;  // queued by every frame while set
    int fault_internal = 0;
    bool initialised = false, device_disabled = false, force_output = false, scheduler = false;
    int frames_open = 0, sets_outside_frame = 0, frames = 0;
    double transform[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int buttons = 0;
    double workspace[6] = {-80, -60, -35, 80, 60, 35};
    double peak = 3.3, continuous = 0.88, stiffness = 1.26, damping = 0.0035;
    std::vector<std::pair<HDSchedulerCallback, void*>> scheduled;
    double force[3] = {0, 0, 0};  // set in the open frame
    double sent[3] = {0, 0, 0};   // committed by the last frame, with force output on
    std::string calls;
};

Fake& fake()
{
    static Fake f;
    return f;
}

void log(Fake& f, const std::string& call) { f.calls += (f.calls.empty() ? "" : " ") + call; }
void error(Fake& f, HDerror code, int internal = 0) { f.errors.push_back({code, internal, 0}); }

}  // namespace

extern "C" {

// ---- the HD API ----
__attribute__((visibility("default"))) HHD hdInitDevice(HDstring config)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, std::string("hdInitDevice(") + (config == HD_DEFAULT_DEVICE ? "HD_DEFAULT_DEVICE" : config) + ")");
    if (f.init_error != HD_SUCCESS) {
        f.errors.push_back({f.init_error, f.init_internal, HD_INVALID_HANDLE});
        return HD_INVALID_HANDLE;
    }
    f.initialised = true;
    f.device_disabled = false;
    return 1;
}
__attribute__((visibility("default"))) void hdDisableDevice(HHD hhd)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdDisableDevice(" + std::to_string(hhd) + ")");
    f.device_disabled = true;
    f.initialised = false;
}
__attribute__((visibility("default"))) void hdMakeCurrentDevice(HHD) {}
__attribute__((visibility("default"))) HDErrorInfo hdGetError()
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    if (f.errors.empty()) return {HD_SUCCESS, 0, 0};
    const HDErrorInfo e = f.errors.front();
    f.errors.pop_front();
    return e;
}
__attribute__((visibility("default"))) HDstring hdGetErrorString(HDerror code)
{
    return code == HD_COMM_ERROR ? "Communication error" : code == HD_DEVICE_FAULT ? "Device fault" : "";
}
__attribute__((visibility("default"))) void hdEnable(HDenum cap)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    char s[32];
    std::snprintf(s, sizeof s, "hdEnable(0x%04x)", cap);
    log(f, s);
    if (cap == HD_FORCE_OUTPUT) f.force_output = true;
}
__attribute__((visibility("default"))) void hdDisable(HDenum cap)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    char s[32];
    std::snprintf(s, sizeof s, "hdDisable(0x%04x)", cap);
    log(f, s);
    if (cap == HD_FORCE_OUTPUT) f.force_output = false;
}
__attribute__((visibility("default"))) void hdBeginFrame(HHD)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    if (f.frames_open++ != 0) error(f, HD_ILLEGAL_BEGIN);
}
__attribute__((visibility("default"))) void hdEndFrame(HHD)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    if (f.frames_open-- != 1) {
        error(f, HD_ILLEGAL_END);
        f.frames_open = 0;
        return;
    }
    ++f.frames;
    if (f.fault != HD_SUCCESS) {
        error(f, f.fault, f.fault_internal);
        return;  // a faulted arm takes no force
    }
    if (f.force_output) std::memcpy(f.sent, f.force, sizeof f.sent);
}
__attribute__((visibility("default"))) void hdGetDoublev(HDenum pname, HDdouble* v)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    switch (pname) {
    case HD_CURRENT_TRANSFORM: std::memcpy(v, f.transform, sizeof f.transform); break;
    case HD_CURRENT_POSITION: v[0] = f.transform[12], v[1] = f.transform[13], v[2] = f.transform[14]; break;
    case HD_USABLE_WORKSPACE_DIMENSIONS: std::memcpy(v, f.workspace, sizeof f.workspace); break;
    case HD_NOMINAL_MAX_FORCE: v[0] = f.peak; break;
    case HD_NOMINAL_MAX_CONTINUOUS_FORCE:
        if (f.continuous > 0) v[0] = f.continuous;
        else error(f, HD_INVALID_ENUM);  // an older arm without the figure
        break;
    case HD_NOMINAL_MAX_STIFFNESS: v[0] = f.stiffness; break;
    case HD_NOMINAL_MAX_DAMPING: v[0] = f.damping; break;
    default: error(f, HD_INVALID_ENUM);
    }
}
__attribute__((visibility("default"))) void hdGetIntegerv(HDenum pname, HDint* v)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    switch (pname) {
    case HD_CURRENT_BUTTONS: v[0] = f.buttons; break;
    case HD_INPUT_DOF: v[0] = 6; break;
    case HD_UPDATE_RATE: v[0] = 1000; break;
    default: error(f, HD_INVALID_ENUM);
    }
}
__attribute__((visibility("default"))) HDstring hdGetString(HDenum pname)
{
    return pname == HD_DEVICE_MODEL_TYPE ? "Touch" : pname == HD_DEVICE_SERIAL_NUMBER ? "FAKE-0001" : nullptr;
}
__attribute__((visibility("default"))) void hdSetDoublev(HDenum pname, const HDdouble* v)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    if (pname != HD_CURRENT_FORCE) {
        error(f, HD_INVALID_ENUM);
        return;
    }
    if (f.frames_open != 1) ++f.sets_outside_frame;
    std::memcpy(f.force, v, sizeof f.force);
    char s[96];
    std::snprintf(s, sizeof s, "force=%g,%g,%g", v[0], v[1], v[2]);
    log(f, s);
}
__attribute__((visibility("default"))) void hdStartScheduler()
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdStartScheduler");
    f.scheduler = true;
}
__attribute__((visibility("default"))) void hdStopScheduler()
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdStopScheduler");
    f.scheduler = false;
}
__attribute__((visibility("default"))) HDSchedulerHandle hdScheduleAsynchronous(HDSchedulerCallback cb, void* data, HDushort)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdScheduleAsynchronous");
    f.scheduled.emplace_back(cb, data);
    return f.scheduled.size();  // 1-based: 0 is never a handle
}
__attribute__((visibility("default"))) void hdScheduleSynchronous(HDSchedulerCallback cb, void* data, HDushort)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdScheduleSynchronous");
    for (int i = 0; i < 1000 && cb(data) == HD_CALLBACK_CONTINUE; ++i) {
    }
}
__attribute__((visibility("default"))) void hdUnschedule(HDSchedulerHandle h)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    log(f, "hdUnschedule");
    if (h >= 1 && h <= f.scheduled.size()) f.scheduled[h - 1] = {nullptr, nullptr};
}

// ---- the test's controls (fake_hd_control.hpp) ----
__attribute__((visibility("default"))) void fake_hd_reset()
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    f.errors.clear();
    f.init_error = f.fault = HD_SUCCESS;
    f.init_internal = f.fault_internal = 0;
    f.initialised = f.device_disabled = f.force_output = f.scheduler = false;
    f.frames_open = f.sets_outside_frame = f.frames = 0;
    const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::memcpy(f.transform, identity, sizeof identity);
    f.buttons = 0;
    const double box[6] = {-80, -60, -35, 80, 60, 35};
    std::memcpy(f.workspace, box, sizeof box);
    f.peak = 3.3, f.continuous = 0.88, f.stiffness = 1.26, f.damping = 0.0035;
    f.scheduled.clear();
    f.force[0] = f.force[1] = f.force[2] = 0;
    f.sent[0] = f.sent[1] = f.sent[2] = 0;
    f.calls.clear();
}
__attribute__((visibility("default"))) void fake_hd_fail_init(HDerror code, int internal)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    f.init_error = code, f.init_internal = internal;
}
__attribute__((visibility("default"))) void fake_hd_set_fault(HDerror code, int internal)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    f.fault = code, f.fault_internal = internal;
}
__attribute__((visibility("default"))) void fake_hd_set_pose(const double transform[16], int buttons)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    std::memcpy(f.transform, transform, sizeof f.transform);
    f.buttons = buttons;
}
__attribute__((visibility("default"))) void fake_hd_set_arm(const double workspace[6], double peak, double continuous, double stiffness, double damping)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    std::memcpy(f.workspace, workspace, sizeof f.workspace);
    f.peak = peak, f.continuous = continuous, f.stiffness = stiffness, f.damping = damping;
}
__attribute__((visibility("default"))) void fake_hd_queue_error(HDerror code)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    error(f, code);
}
__attribute__((visibility("default"))) int fake_hd_servo(int ticks)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    int ran = 0;
    for (int i = 0; i < ticks && f.scheduler; ++i)
        for (auto& [cb, data] : f.scheduled)
            if (cb != nullptr) {
                ++ran;
                if (cb(data) == HD_CALLBACK_DONE) cb = nullptr;
            }
    return ran;
}
__attribute__((visibility("default"))) void fake_hd_sent_force(double out[3])
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    std::memcpy(out, f.sent, sizeof f.sent);
}
__attribute__((visibility("default"))) int fake_hd_state(const char* what)
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    const std::string w = what;
    if (w == "initialised") return f.initialised;
    if (w == "device_disabled") return f.device_disabled;
    if (w == "force_output") return f.force_output;
    if (w == "scheduler") return f.scheduler;
    if (w == "frames") return f.frames;
    if (w == "frames_open") return f.frames_open;
    if (w == "sets_outside_frame") return f.sets_outside_frame;
    if (w == "scheduled") {
        int n = 0;
        for (const auto& s : f.scheduled) n += s.first != nullptr;
        return n;
    }
    return -1;
}
__attribute__((visibility("default"))) const char* fake_hd_calls()
{
    Fake& f = fake();
    const std::lock_guard lock(f.mutex);
    return f.calls.c_str();
}

}  // extern "C"

// The part of 3D Systems' OpenHaptics HD API (libHD.so) the Touch/Phantom driver uses, declared here
// and loaded at run time: OpenHaptics is not in Debian, so echosim builds without it and finds it
// where the vendor's installer put it. No vendor header is copied: the types, values and C
// signatures below are those of OpenHaptics' hd.h, hdDefines.h and hdScheduler.h (3.x, Linux, where
// HDAPI and HDCALLBACK are empty), the few we call.
//
// HdApi is a table of the library's functions. load_hd_library fills it with dlopen/dlsym, and keeps
// the library loaded for as long as any copy of the table lives; a test fills it from a fake libHD
// built for the purpose (tests/device/fake_hd), through the same loader.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace echosim::device::hd {

// hdDefines.h's types (LP64 Linux)
using HHD = unsigned int;
using HDenum = unsigned int;
using HDerror = unsigned int;
using HDint = int;
using HDdouble = double;
using HDushort = unsigned short;
using HDstring = const char*;
using HDCallbackCode = unsigned int;
using HDSchedulerHandle = unsigned long;
using HDSchedulerCallback = HDCallbackCode (*)(void* user_data);

struct HDErrorInfo {
    HDerror errorCode;      // an HD_ error code, HD_SUCCESS when none
    int internalErrorCode;  // the device driver's own
    HHD hHD;                // the device current when it happened
};

inline constexpr HDstring HD_DEFAULT_DEVICE = nullptr;
inline constexpr HHD HD_INVALID_HANDLE = 0xFFFFFFFFu;
inline constexpr HDCallbackCode HD_CALLBACK_DONE = 0;
inline constexpr HDCallbackCode HD_CALLBACK_CONTINUE = 1;
inline constexpr HDushort HD_MAX_SCHEDULER_PRIORITY = 0xFFFF;

// errors
inline constexpr HDerror HD_SUCCESS = 0x0000;
inline constexpr HDerror HD_INVALID_ENUM = 0x0100;
inline constexpr HDerror HD_INVALID_VALUE = 0x0101;
inline constexpr HDerror HD_INVALID_OPERATION = 0x0102;
inline constexpr HDerror HD_INVALID_INPUT_TYPE = 0x0103;
inline constexpr HDerror HD_BAD_HANDLE = 0x0104;
inline constexpr HDerror HD_WARM_MOTORS = 0x0200;
inline constexpr HDerror HD_EXCEEDED_MAX_FORCE = 0x0201;
inline constexpr HDerror HD_EXCEEDED_MAX_FORCE_IMPULSE = 0x0202;
inline constexpr HDerror HD_EXCEEDED_MAX_VELOCITY = 0x0203;
inline constexpr HDerror HD_FORCE_ERROR = 0x0204;
inline constexpr HDerror HD_DEVICE_FAULT = 0x0300;
inline constexpr HDerror HD_DEVICE_ALREADY_INITIATED = 0x0301;
inline constexpr HDerror HD_COMM_ERROR = 0x0302;
inline constexpr HDerror HD_COMM_CONFIG_ERROR = 0x0303;
inline constexpr HDerror HD_TIMER_ERROR = 0x0304;
inline constexpr HDerror HD_ILLEGAL_BEGIN = 0x0400;
inline constexpr HDerror HD_ILLEGAL_END = 0x0401;
inline constexpr HDerror HD_FRAME_ERROR = 0x0402;
inline constexpr HDerror HD_INVALID_PRIORITY = 0x0500;
inline constexpr HDerror HD_SCHEDULER_FULL = 0x0501;
inline constexpr HDerror HD_INVALID_LICENSE = 0x0600;

// parameters (hdGet*v, hdSetDoublev, hdGetString)
inline constexpr HDenum HD_CURRENT_BUTTONS = 0x2000;             // 1 int: bit i, button i held
inline constexpr HDenum HD_CURRENT_POSITION = 0x2050;            // 3 doubles [mm]
inline constexpr HDenum HD_CURRENT_TRANSFORM = 0x2052;           // 16 doubles, column-major 4x4 [mm]
inline constexpr HDenum HD_DEVICE_MODEL_TYPE = 0x2501;           // string
inline constexpr HDenum HD_DEVICE_SERIAL_NUMBER = 0x2504;        // string
inline constexpr HDenum HD_USABLE_WORKSPACE_DIMENSIONS = 0x2551; // 6 doubles: min x, y, z, max x, y, z [mm]
inline constexpr HDenum HD_INPUT_DOF = 0x2553;                   // 1 int
inline constexpr HDenum HD_UPDATE_RATE = 0x2600;                 // 1 int [Hz]
inline constexpr HDenum HD_NOMINAL_MAX_STIFFNESS = 0x2602;       // 1 double [N/mm]
inline constexpr HDenum HD_NOMINAL_MAX_FORCE = 0x2603;           // 1 double [N], the peak
inline constexpr HDenum HD_NOMINAL_MAX_CONTINUOUS_FORCE = 0x2604;  // 1 double [N]
inline constexpr HDenum HD_NOMINAL_MAX_DAMPING = 0x2609;         // 1 double [N s/mm]
inline constexpr HDenum HD_CURRENT_FORCE = 0x2700;               // 3 doubles [N], the device's frame
// capabilities (hdEnable, hdDisable)
inline constexpr HDenum HD_FORCE_OUTPUT = 0x4000;

// The functions, by the names libHD exports them under.
struct HdApi {
    HHD (*hdInitDevice)(HDstring config_name) = nullptr;
    void (*hdDisableDevice)(HHD hhd) = nullptr;
    void (*hdMakeCurrentDevice)(HHD hhd) = nullptr;
    HDErrorInfo (*hdGetError)() = nullptr;
    HDstring (*hdGetErrorString)(HDerror code) = nullptr;
    void (*hdEnable)(HDenum cap) = nullptr;
    void (*hdDisable)(HDenum cap) = nullptr;
    void (*hdBeginFrame)(HHD hhd) = nullptr;
    void (*hdEndFrame)(HHD hhd) = nullptr;
    void (*hdGetDoublev)(HDenum pname, HDdouble* params) = nullptr;
    void (*hdGetIntegerv)(HDenum pname, HDint* params) = nullptr;
    HDstring (*hdGetString)(HDenum pname) = nullptr;
    void (*hdSetDoublev)(HDenum pname, const HDdouble* params) = nullptr;
    void (*hdStartScheduler)() = nullptr;
    void (*hdStopScheduler)() = nullptr;
    HDSchedulerHandle (*hdScheduleAsynchronous)(HDSchedulerCallback callback, void* user_data, HDushort priority) = nullptr;
    void (*hdScheduleSynchronous)(HDSchedulerCallback callback, void* user_data, HDushort priority) = nullptr;
    void (*hdUnschedule)(HDSchedulerHandle handle) = nullptr;

    std::string path;                  // the library it came from, for messages
    std::shared_ptr<void> library;     // keeps it loaded (dlclose when the last copy goes)
};

// What load_hd_library found: the table, or why there is none (each place tried, and what failed).
struct HdLoad {
    std::shared_ptr<const HdApi> api;  // null: not loaded
    std::string error;
};

// Where OpenHaptics' library is looked for, in order: $ECHOSIM_OPENHAPTICS_LIBRARY if set, then
// libHD.so through the dynamic linker's own search (ld.so.conf, LD_LIBRARY_PATH), then the folders
// OpenHaptics for Linux installs into.
std::vector<std::string> hd_library_candidates();
// Loads the first candidate that opens and has every function above; never throws for want of it.
HdLoad load_hd_library(const std::vector<std::string>& candidates = hd_library_candidates());

// "HD_COMM_ERROR (0x0302)"
std::string hd_error_name(HDerror code);
// The error with the library's own words when it has them: "HD_COMM_ERROR (0x0302, internal 5): ..."
std::string describe(const HdApi& api, const HDErrorInfo& e);

// What a user does when libHD is not there (one sentence, for `echosim devices` and the run's refusal)
inline constexpr const char* kInstallHint =
    "install 3D Systems' OpenHaptics for Linux and the Touch device driver (not in Debian; from 3D Systems' support "
    "site), run Touch_Setup to pair the arm, or point ECHOSIM_OPENHAPTICS_LIBRARY at its libHD.so";

}  // namespace echosim::device::hd

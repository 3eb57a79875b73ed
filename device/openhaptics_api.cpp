#include "device/openhaptics_api.hpp"

#include <cstdio>
#include <cstdlib>

#include <dlfcn.h>

namespace echosim::device::hd {
namespace {

// one symbol into its slot; false (and why, in `missing`) when the library lacks it
template <class F>
bool bind(void* library, const char* name, F& slot, std::string& missing)
{
    void* symbol = dlsym(library, name);
    if (symbol == nullptr) {
        missing += missing.empty() ? name : std::string(", ") + name;
        return false;
    }
    slot = reinterpret_cast<F>(symbol);
    return true;
}

}  // namespace

std::vector<std::string> hd_library_candidates()
{
    std::vector<std::string> c;
    if (const char* env = std::getenv("ECHOSIM_OPENHAPTICS_LIBRARY"); env != nullptr && *env != '\0') c.emplace_back(env);
    c.emplace_back("libHD.so");
    // OpenHaptics for Linux's installers put it in lib64 folders Debian's linker does not search
    c.emplace_back("/usr/lib64/libHD.so");
    c.emplace_back("/usr/local/lib64/libHD.so");
    return c;
}

HdLoad load_hd_library(const std::vector<std::string>& candidates)
{
    HdLoad out;
    for (const std::string& path : candidates) {
        // RTLD_LOCAL: its symbols stay its own (a test loads a fake beside nothing else)
        void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (library == nullptr) {
            const char* why = dlerror();
            out.error += (out.error.empty() ? "" : "; ") + std::string(why != nullptr ? why : path + ": cannot open");
            continue;
        }
        auto api = std::make_shared<HdApi>();
        api->library = std::shared_ptr<void>(library, [](void* l) { dlclose(l); });
        api->path = path;
        if (Dl_info info{}; dladdr(dlsym(library, "hdInitDevice"), &info) != 0 && info.dli_fname != nullptr) api->path = info.dli_fname;
        std::string missing;
        bind(library, "hdInitDevice", api->hdInitDevice, missing);
        bind(library, "hdDisableDevice", api->hdDisableDevice, missing);
        bind(library, "hdMakeCurrentDevice", api->hdMakeCurrentDevice, missing);
        bind(library, "hdGetError", api->hdGetError, missing);
        bind(library, "hdGetErrorString", api->hdGetErrorString, missing);
        bind(library, "hdEnable", api->hdEnable, missing);
        bind(library, "hdDisable", api->hdDisable, missing);
        bind(library, "hdBeginFrame", api->hdBeginFrame, missing);
        bind(library, "hdEndFrame", api->hdEndFrame, missing);
        bind(library, "hdGetDoublev", api->hdGetDoublev, missing);
        bind(library, "hdGetIntegerv", api->hdGetIntegerv, missing);
        bind(library, "hdGetString", api->hdGetString, missing);
        bind(library, "hdSetDoublev", api->hdSetDoublev, missing);
        bind(library, "hdStartScheduler", api->hdStartScheduler, missing);
        bind(library, "hdStopScheduler", api->hdStopScheduler, missing);
        bind(library, "hdScheduleAsynchronous", api->hdScheduleAsynchronous, missing);
        bind(library, "hdScheduleSynchronous", api->hdScheduleSynchronous, missing);
        bind(library, "hdUnschedule", api->hdUnschedule, missing);
        if (!missing.empty()) {
            out.error += (out.error.empty() ? "" : "; ") + api->path + " lacks " + missing + " (not OpenHaptics' HD library?)";
            continue;  // the shared_ptr closes it
        }
        out.api = std::move(api);
        out.error.clear();
        return out;
    }
    if (out.error.empty()) out.error = "nowhere to look";
    return out;
}

namespace {

const char* error_symbol(HDerror code)
{
    switch (code) {
    case HD_SUCCESS: return "HD_SUCCESS";
    case HD_INVALID_ENUM: return "HD_INVALID_ENUM";
    case HD_INVALID_VALUE: return "HD_INVALID_VALUE";
    case HD_INVALID_OPERATION: return "HD_INVALID_OPERATION";
    case HD_INVALID_INPUT_TYPE: return "HD_INVALID_INPUT_TYPE";
    case HD_BAD_HANDLE: return "HD_BAD_HANDLE";
    case HD_WARM_MOTORS: return "HD_WARM_MOTORS";
    case HD_EXCEEDED_MAX_FORCE: return "HD_EXCEEDED_MAX_FORCE";
    case HD_EXCEEDED_MAX_FORCE_IMPULSE: return "HD_EXCEEDED_MAX_FORCE_IMPULSE";
    case HD_EXCEEDED_MAX_VELOCITY: return "HD_EXCEEDED_MAX_VELOCITY";
    case HD_FORCE_ERROR: return "HD_FORCE_ERROR";
    case HD_DEVICE_FAULT: return "HD_DEVICE_FAULT";
    case HD_DEVICE_ALREADY_INITIATED: return "HD_DEVICE_ALREADY_INITIATED";
    case HD_COMM_ERROR: return "HD_COMM_ERROR";
    case HD_COMM_CONFIG_ERROR: return "HD_COMM_CONFIG_ERROR";
    case HD_TIMER_ERROR: return "HD_TIMER_ERROR";
    case HD_ILLEGAL_BEGIN: return "HD_ILLEGAL_BEGIN";
    case HD_ILLEGAL_END: return "HD_ILLEGAL_END";
    case HD_FRAME_ERROR: return "HD_FRAME_ERROR";
    case HD_INVALID_PRIORITY: return "HD_INVALID_PRIORITY";
    case HD_SCHEDULER_FULL: return "HD_SCHEDULER_FULL";
    case HD_INVALID_LICENSE: return "HD_INVALID_LICENSE";
    default: return "HD error";
    }
}

std::string named(HDerror code, const std::string& more)
{
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04x", code);
    return std::string(error_symbol(code)) + " (" + hex + more + ")";
}

}  // namespace

std::string hd_error_name(HDerror code) { return named(code, ""); }

std::string describe(const HdApi& api, const HDErrorInfo& e)
{
    std::string s = named(e.errorCode, e.internalErrorCode != 0 ? ", internal " + std::to_string(e.internalErrorCode) : "");
    const HDstring words = api.hdGetErrorString != nullptr ? api.hdGetErrorString(e.errorCode) : nullptr;
    if (words != nullptr && *words != '\0') s += std::string(": ") + words;
    return s;
}

}  // namespace echosim::device::hd

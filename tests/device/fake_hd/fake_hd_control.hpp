// The test's side of the fake libHD (fake_hd.cpp): its controls, found in the same loaded library as
// the driver's functions (dlopen of the same path gives the same library, so one fake arm).
#pragma once

#include <stdexcept>
#include <string>

#include <dlfcn.h>

#include "device/openhaptics_api.hpp"

namespace echosim::test {

struct FakeHd {
    explicit FakeHd(const std::string& path) : library(dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL))
    {
        if (library == nullptr) throw std::runtime_error("fake libHD: " + std::string(dlerror()));
        bind("fake_hd_reset", reset);
        bind("fake_hd_fail_init", fail_init);
        bind("fake_hd_set_fault", set_fault);
        bind("fake_hd_set_pose", set_pose);
        bind("fake_hd_set_arm", set_arm);
        bind("fake_hd_queue_error", queue_error);
        bind("fake_hd_servo", servo);
        bind("fake_hd_sent_force", sent_force);
        bind("fake_hd_state", state);
        bind("fake_hd_calls", calls);
        reset();
    }
    ~FakeHd() { dlclose(library); }
    FakeHd(const FakeHd&) = delete;
    FakeHd& operator=(const FakeHd&) = delete;

    void* library;
    void (*reset)() = nullptr;
    void (*fail_init)(device::hd::HDerror code, int internal) = nullptr;
    void (*set_fault)(device::hd::HDerror code, int internal) = nullptr;  // HD_SUCCESS clears it
    void (*set_pose)(const double transform[16], int buttons) = nullptr;
    void (*set_arm)(const double workspace[6], double peak, double continuous, double stiffness, double damping) = nullptr;
    void (*queue_error)(device::hd::HDerror code) = nullptr;
    int (*servo)(int ticks) = nullptr;  // runs the scheduled callbacks `ticks` times; how many ran
    void (*sent_force)(double out[3]) = nullptr;
    int (*state)(const char* what) = nullptr;
    const char* (*calls)() = nullptr;

private:
    template <class F>
    void bind(const char* name, F& slot)
    {
        void* s = dlsym(library, name);
        if (s == nullptr) throw std::runtime_error(std::string("fake libHD lacks ") + name);
        slot = reinterpret_cast<F>(s);
    }
};

}  // namespace echosim::test

// GPU tests run on Mesa lavapipe (what CI has, and what the reference images were drawn with),
// with the Khronos validation layer on. ECHOSIM_TEST_GPU names another device (as --gpu does) for
// the checks a lent GPU is used for: the kernels against their CPU twins on real hardware
// (bench/device/gpu_checks.sh). The reference-image tests hold for lavapipe alone.
#pragma once

#include <cstdlib>

#include "gpu/context.hpp"

namespace echosim::test {

inline gpu::ContextOptions lavapipe_options()
{
    gpu::ContextOptions o;
    o.validation = true;
    const char* other = std::getenv("ECHOSIM_TEST_GPU");
    o.gpu = other && *other ? other : "cpu";
    return o;
}

}  // namespace echosim::test

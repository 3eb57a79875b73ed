// GPU tests run on Mesa lavapipe (what CI has, and what the reference images were drawn with),
// with the Khronos validation layer on.
#pragma once

#include "gpu/context.hpp"

namespace echosim::test {

inline gpu::ContextOptions lavapipe_options()
{
    gpu::ContextOptions o;
    o.validation = true;
    o.gpu = "cpu";
    return o;
}

}  // namespace echosim::test

#pragma once

#include "app/commands.hpp"
#include "gpu/context.hpp"

namespace echosim::app {

// Command-line choices over the environment's.
inline gpu::ContextOptions context_options(const GpuArgs& args)
{
    gpu::ContextOptions o = gpu::ContextOptions::from_environment();
    if (!args.gpu.empty()) o.gpu = args.gpu;
    if (args.validation) o.validation = true;
    return o;
}

}  // namespace echosim::app

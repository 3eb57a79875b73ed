// Which B-mode imager makes a sweep's frames (issue 33): the GPU kernels (image/bmode_gpu.hpp) when
// a Vulkan device is at hand, the CPU twin (echo::CpuSweepImager) when asked for (`--cpu`) or when
// no device can be made, with a line on stderr saying why. The echo layer cannot see the GPU, so
// the choice is made here and handed down as echo::CaseVolumeOptions::imager.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "echo/case_volume.hpp"
#include "echo/sweep.hpp"
#include "gpu/context.hpp"

namespace echosim::app {

// The GPU's imager for `labels` and `spec` on the device `options` pick (owning its context), or,
// when none can be made, the CPU twin after telling stderr "`command`: no usable Vulkan device
// (REASON): synthesising on the CPU".
std::unique_ptr<echo::SweepImager> make_bmode_imager(std::shared_ptr<const io::Volume> labels, const echo::ScanSpec& spec,
                                                     const gpu::ContextOptions& options, const std::string& command);

// make_bmode_imager as a case volume's imager.
inline std::function<std::unique_ptr<echo::SweepImager>(std::shared_ptr<const io::Volume>, const echo::ScanSpec&)> bmode_imager_factory(
    const gpu::ContextOptions& options, const std::string& command)
{
    return [options, command](std::shared_ptr<const io::Volume> labels, const echo::ScanSpec& spec) {
        return make_bmode_imager(std::move(labels), spec, options, command);
    };
}

}  // namespace echosim::app

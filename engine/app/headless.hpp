// One headless frame, end to end: context, the scene pass, offscreen presenter, readback. Used by
// `echosim render`, the render tests and the benchmarks.
#pragma once

#include <string>

#include "gpu/context.hpp"
#include "render/scene_pass.hpp"
#include "io/png.hpp"

namespace echosim::app {

struct HeadlessFrame {
    io::RgbaImage image;
    std::string device;                   // the Vulkan device that drew it
    std::uint32_t validation_messages = 0;  // counted until the device was destroyed (leaks included)
};

HeadlessFrame render_headless(const gpu::ContextOptions& options, const render::SceneMeshes& meshes, const render::FrameView& view,
                              std::uint32_t width, std::uint32_t height);

}  // namespace echosim::app

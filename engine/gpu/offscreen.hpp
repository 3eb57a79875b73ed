// The headless presenter: renders into an offscreen image and reads it back to host memory. It is
// a first-class presenter (Granite's headless platform): `echosim render`, the render tests, the
// benchmarks and CI all draw through it with the same renderer the window uses.
#pragma once

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/renderer.hpp"
#include "gpu/resources.hpp"
#include "io/png.hpp"

namespace echosim::gpu {

class OffscreenPresenter {
public:
    static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_SRGB;  // bytes read back are sRGB, ready for PNG

    OffscreenPresenter(const Context& ctx, VkExtent2D extent);
    ~OffscreenPresenter();
    OffscreenPresenter(const OffscreenPresenter&) = delete;
    OffscreenPresenter& operator=(const OffscreenPresenter&) = delete;

    VkExtent2D extent() const { return color_.extent(); }

    // Draws one frame and waits for it; with `readback` the pixels are copied back into `out`.
    void render(Renderer& renderer, const FrameView& view, io::RgbaImage* out);

private:
    const Context& ctx_;
    Image color_;
    Buffer readback_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace echosim::gpu

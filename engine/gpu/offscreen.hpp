// The headless presenter: renders into an offscreen image and reads it back to host memory. It is
// a first-class presenter (Granite's headless platform): `echosim render`, the render tests, the
// benchmarks and CI all draw through it with the same passes the window uses.
//
// Each frame is waited for, so any frame slot is free when the next one starts; the presenter
// still takes the slots in turn, as the window does, so per-slot resources are exercised headless.
//
// Threading: the presenter records and submits through the command pool it is given, the calling
// thread's one pool (command_pool.hpp), so it renders on that thread only.
#pragma once

#include <vulkan/vulkan.h>

#include "gpu/command_pool.hpp"
#include "gpu/context.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "io/png.hpp"

namespace echosim::gpu {

class OffscreenPresenter {
public:
    // The window's kind of target (gpu/window.cpp): the passes write sRGB-encoded bytes, ready for
    // PNG. R8G8B8A8_SRGB, the window's fallback, gives the same bytes, the target encoding them.
    static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
    static constexpr VkImageUsageFlags kUsage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

    // `commands`: the calling thread's pool (on its context); it must outlive the presenter.
    OffscreenPresenter(CommandPool& commands, VkExtent2D extent, VkFormat format = kFormat);
    ~OffscreenPresenter();
    OffscreenPresenter(const OffscreenPresenter&) = delete;
    OffscreenPresenter& operator=(const OffscreenPresenter&) = delete;

    VkExtent2D extent() const { return color_.extent(); }
    VkFormat format() const { return color_.format(); }

    // Records the passes into one frame, submits it and waits for it; with `out` the pixels are
    // copied back into it.
    void render(const FramePasses& passes, io::RgbaImage* out);

private:
    void record(VkCommandBuffer cmd, const FramePasses& passes, bool readback);

    const Context& ctx_;
    CommandPool& commands_;
    Image color_;
    Buffer readback_;
    int slot_ = 0;
};

}  // namespace echosim::gpu

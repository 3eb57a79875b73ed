// One presenter interface for the runner (Granite's platforms: a window or headless behind one
// verb): present(passes) records the frame's passes into the output's target and shows the frame,
// in a window, or finishes it offscreen, where it can also be read back for recorders.
//
// Threading: both present on the thread that made them (the window's on the main thread, GLFW's
// rule), through that thread's command pool.
#pragma once

#include <memory>

#include "gpu/command_pool.hpp"
#include "gpu/frame.hpp"
#include "gpu/offscreen.hpp"
#include "gpu/window.hpp"
#include "io/png.hpp"

namespace echosim::runner {

class Presenter {
public:
    virtual ~Presenter() = default;
    virtual VkFormat format() const = 0;
    virtual VkExtent2D extent() const = 0;
    // Whether present() can read a frame back (offscreen; a window cannot).
    virtual bool can_read_back() const = 0;
    // Records `passes` into one frame and shows it (a window: FIFO, paced by the display) or finishes
    // it (offscreen: submitted and waited for); with `pixels` and can_read_back(), the frame's pixels
    // are read back into it (RGBA, sRGB-encoded). Returns whether a frame was drawn: a minimised
    // window draws none, and waits up to 50 ms for its events instead, so a loop does not spin.
    virtual bool present(const gpu::FramePasses& passes, io::RgbaImage* pixels) = 0;
};

class OffscreenOutput final : public Presenter {
public:
    OffscreenOutput(gpu::CommandPool& commands, VkExtent2D extent) : presenter_(commands, extent) {}
    VkFormat format() const override { return presenter_.format(); }
    VkExtent2D extent() const override { return presenter_.extent(); }
    bool can_read_back() const override { return true; }
    bool present(const gpu::FramePasses& passes, io::RgbaImage* pixels) override;

private:
    gpu::OffscreenPresenter presenter_;
};

class WindowOutput final : public Presenter {
public:
    // `window` must outlive the output.
    WindowOutput(gpu::CommandPool& commands, gpu::Window& window) : window_(window), presenter_(commands, window) {}
    VkFormat format() const override { return presenter_.format(); }
    VkExtent2D extent() const override { return presenter_.extent(); }
    bool can_read_back() const override { return false; }
    bool present(const gpu::FramePasses& passes, io::RgbaImage* pixels) override;
    gpu::Window& window() { return window_; }
    std::uint32_t swapchain_generation() const { return presenter_.swapchain_generation(); }

private:
    gpu::Window& window_;
    gpu::WindowPresenter presenter_;
};

}  // namespace echosim::runner

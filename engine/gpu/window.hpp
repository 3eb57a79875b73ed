// The windowed presenter: a GLFW window and its Vulkan swapchain. It survives resizes, minimising
// (a zero-sized framebuffer: nothing is drawn until the window comes back) and switches between
// windowed and fullscreen at any size the monitor offers, up to 3840x2160 and beyond.
//
// Threading: GLFW requires the window to be made, polled and destroyed on the main thread. The
// presenter records its frames into command buffers of the pool it is given, the drawing thread's
// one pool (command_pool.hpp); it submits and presents through the Context.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/command_pool.hpp"
#include "gpu/context.hpp"
#include "gpu/frame.hpp"

struct GLFWwindow;

namespace echosim::gpu {

// Whether a window system can be reached at all (X11 or Wayland display), and why not.
struct DisplayProbe {
    bool available = false;
    std::string reason;
};
DisplayProbe probe_display();

struct WindowOptions {
    int width = 1600;
    int height = 900;
    bool fullscreen = false;
    std::string title = "echosim";
};

// The GLFW library and one window. Throws with GLFW's own description when either cannot be made.
class Window {
public:
    explicit Window(const WindowOptions& options);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    static std::vector<std::string> required_instance_extensions();
    static bool can_present(VkInstance instance, VkPhysicalDevice device, std::uint32_t family);

    bool should_close() const;
    void set_fullscreen(bool on);
    bool fullscreen() const { return fullscreen_; }
    VkExtent2D framebuffer_extent() const;

private:
    GLFWwindow* window_ = nullptr;
    bool fullscreen_ = false;
    int windowed_x_ = 100, windowed_y_ = 100, windowed_w_ = 0, windowed_h_ = 0;
};

class WindowPresenter {
public:
    // `commands`: the drawing thread's pool (on a context made for this window, see
    // Window::can_present); it and the window must outlive the presenter. Throws, having released
    // what it made, when the surface or the swapchain cannot be made.
    WindowPresenter(CommandPool& commands, Window& window);
    ~WindowPresenter();
    WindowPresenter(const WindowPresenter&) = delete;
    WindowPresenter& operator=(const WindowPresenter&) = delete;

    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    std::uint32_t swapchain_generation() const { return generation_; }  // how many times (re)created

    // Records the passes into one frame (slot after slot, kFramesInFlight in flight) and presents
    // it; returns false when nothing could be drawn (minimised window).
    bool draw(const FramePasses& passes);

private:
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence in_flight = VK_NULL_HANDLE;
        VkSemaphore image_acquired = VK_NULL_HANDLE;
    };

    void create_swapchain();
    void destroy_swapchain_views();
    void destroy();

    const Context& ctx_;
    CommandPool& commands_;
    Window& window_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageUsageFlags usage_ = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> render_done_;  // one per swapchain image: present waits on it
    std::array<Frame, kFramesInFlight> frames_{};
    int frame_ = 0;
    std::uint32_t generation_ = 0;
};

}  // namespace echosim::gpu

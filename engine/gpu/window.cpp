#include "gpu/window.hpp"

#include <algorithm>
#include <cstdlib>
#include <span>
#include <stdexcept>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gpu/vk_error.hpp"

namespace echosim::gpu {
namespace {

std::string glfw_error()
{
    const char* description = nullptr;
    const int code = glfwGetError(&description);
    return code == GLFW_NO_ERROR ? std::string("unknown GLFW error") : std::string(description ? description : "?");
}

}  // namespace

DisplayProbe probe_display()
{
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!x11 || !*x11) && (!wayland || !*wayland))
        return {false, "no display: neither DISPLAY nor WAYLAND_DISPLAY is set"};
    if (!glfwInit()) return {false, "cannot connect to the display: " + glfw_error()};
    const bool vulkan = glfwVulkanSupported() == GLFW_TRUE;
    glfwTerminate();
    if (!vulkan) return {false, "the window system offers no Vulkan surface (is libvulkan1 installed?)"};
    return {true, {}};
}

Window::Window(const WindowOptions& options)
{
    if (!glfwInit()) throw std::runtime_error("cannot start GLFW: " + glfw_error());
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = glfw_error();
        glfwTerminate();
        throw std::runtime_error("cannot open a " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                                 " window: " + why);
    }
    if (options.fullscreen) set_fullscreen(true);
}

Window::~Window()
{
    glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<std::string> Window::required_instance_extensions()
{
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw std::runtime_error("GLFW found no Vulkan surface extensions: " + glfw_error());
    return {names, names + count};
}

bool Window::can_present(VkInstance instance, VkPhysicalDevice device, std::uint32_t family)
{
    return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
}

bool Window::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void Window::set_fullscreen(bool on)
{
    if (on == fullscreen_) return;
    if (on) {
        GLFWmonitor* monitor = glfwGetPrimaryMonitor();
        const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
        if (!mode) return;  // no monitor to fill (some virtual displays): stay windowed
        glfwGetWindowPos(window_, &windowed_x_, &windowed_y_);
        glfwGetWindowSize(window_, &windowed_w_, &windowed_h_);
        glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    } else {
        glfwSetWindowMonitor(window_, nullptr, windowed_x_, windowed_y_, std::max(windowed_w_, 320),
                             std::max(windowed_h_, 240), GLFW_DONT_CARE);
    }
    fullscreen_ = on;
}

VkExtent2D Window::framebuffer_extent() const
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {std::uint32_t(std::max(w, 0)), std::uint32_t(std::max(h, 0))};
}

WindowPresenter::WindowPresenter(CommandPool& commands, Window& window)
    : ctx_(commands.context()), commands_(commands), window_(window)
{
    const Context& ctx = ctx_;
    check(glfwCreateWindowSurface(ctx.instance(), window.handle(), nullptr, &surface_), "glfwCreateWindowSurface");
    try {
        VkBool32 supported = VK_FALSE;
        vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical_device(), ctx.queue_family(), surface_, &supported);
        if (!supported) throw std::runtime_error("the Vulkan queue of " + ctx.device_name() + " cannot present to this window");

        // Prefer an 8-bit UNORM swapchain holding sRGB-encoded bytes, as offscreen: the passes encode
        // (per vertex where they can) and the image panel passes its display bytes through, where an
        // sRGB format would encode every pixel written (on lavapipe, about 7 % of the window's
        // frame). Else an sRGB format, which the passes write linear colour to (they ask the target's
        // format: render/scene_pass.cpp, render/image_panel_pass.cpp).
        std::uint32_t n = 0;
        vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device(), surface_, &n, nullptr);
        std::vector<VkSurfaceFormatKHR> formats(n);
        vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device(), surface_, &n, formats.data());
        if (formats.empty()) throw std::runtime_error("the window surface offers no formats");
        const auto offered = [&](std::initializer_list<VkFormat> wanted) {
            for (VkFormat w : wanted)
                for (const auto& f : formats)
                    if (f.format == w && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return w;
            return VK_FORMAT_UNDEFINED;
        };
        format_ = offered({VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM});
        if (format_ == VK_FORMAT_UNDEFINED) format_ = offered({VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB});
        if (format_ == VK_FORMAT_UNDEFINED) format_ = formats[0].format;

        const VkDevice dev = ctx.device();
        for (Frame& f : frames_) {
            f.cmd = commands_.allocate();
            VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
            fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
            check(vkCreateFence(dev, &fence, nullptr, &f.in_flight), "vkCreateFence");
            VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            check(vkCreateSemaphore(dev, &sem, nullptr, &f.image_acquired), "vkCreateSemaphore");
        }
        create_swapchain();
    } catch (...) {
        destroy();
        throw;
    }
}

WindowPresenter::~WindowPresenter() { destroy(); }

void WindowPresenter::destroy()
{
    const VkDevice dev = ctx_.device();
    ctx_.wait_idle();
    destroy_swapchain_views();
    if (swapchain_) vkDestroySwapchainKHR(dev, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
    for (Frame& f : frames_) {
        if (f.cmd) commands_.free(f.cmd);
        if (f.in_flight) vkDestroyFence(dev, f.in_flight, nullptr);
        if (f.image_acquired) vkDestroySemaphore(dev, f.image_acquired, nullptr);
        f = Frame{};
    }
    if (surface_) vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
}

void WindowPresenter::destroy_swapchain_views()
{
    const VkDevice dev = ctx_.device();
    for (VkImageView v : views_) vkDestroyImageView(dev, v, nullptr);
    for (VkSemaphore s : render_done_) vkDestroySemaphore(dev, s, nullptr);
    views_.clear();
    render_done_.clear();
    images_.clear();
}

void WindowPresenter::create_swapchain()
{
    const VkDevice dev = ctx_.device();
    ctx_.wait_idle();
    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physical_device(), surface_, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) extent = window_.framebuffer_extent();
    extent.width = std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    if (extent.width == 0 || extent.height == 0) return;  // minimised: try again when it is back

    std::uint32_t image_count = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = image_count;
    info.imageFormat = format_;
    info.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    // passes may also clear or blit into the target where the surface allows (FrameTarget::usage)
    usage_ = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    info.imageUsage = usage_;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    // FIFO is always there and paces the loop to the display: the kiosk never spins the CPU
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    check(vkCreateSwapchainKHR(dev, &info, nullptr, &created), "vkCreateSwapchainKHR");
    destroy_swapchain_views();
    if (swapchain_) vkDestroySwapchainKHR(dev, swapchain_, nullptr);
    swapchain_ = created;
    extent_ = extent;
    ++generation_;

    std::uint32_t n = 0;
    vkGetSwapchainImagesKHR(dev, swapchain_, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(dev, swapchain_, &n, images_.data());
    for (VkImage image : images_) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format_;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        check(vkCreateImageView(dev, &view, nullptr, &v), "vkCreateImageView (swapchain)");
        views_.push_back(v);
        VkSemaphoreCreateInfo sem{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore s = VK_NULL_HANDLE;
        check(vkCreateSemaphore(dev, &sem, nullptr, &s), "vkCreateSemaphore");
        render_done_.push_back(s);
    }
}

bool WindowPresenter::draw(const FramePasses& passes)
{
    const VkDevice dev = ctx_.device();
    const VkExtent2D fb = window_.framebuffer_extent();
    if (fb.width == 0 || fb.height == 0) return false;  // minimised
    if (!swapchain_ || fb.width != extent_.width || fb.height != extent_.height) create_swapchain();
    if (!swapchain_) return false;

    Frame& f = frames_[std::size_t(frame_)];
    check(vkWaitForFences(dev, 1, &f.in_flight, VK_TRUE, UINT64_MAX), "vkWaitForFences (frame)");

    std::uint32_t index = 0;
    VkResult acquired = vkAcquireNextImageKHR(dev, swapchain_, UINT64_MAX, f.image_acquired, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        create_swapchain();
        return false;
    }
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");

    check(vkResetFences(dev, 1, &f.in_flight), "vkResetFences");
    check(vkResetCommandBuffer(f.cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(f.cmd, &begin), "vkBeginCommandBuffer");
    const FrameTarget target{images_[index], views_[index], extent_, format_, usage_};
    // the submission waits for the acquired image at the colour output stage; the first barrier
    // starts from that stage, so it chains with the wait whatever stage the first pass needs
    const TargetState initial{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE};
    const TargetState final{VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
    passes.record(f.cmd, frame_, target, initial, final);
    check(vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");

    const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &f.image_acquired;
    submit.pWaitDstStageMask = &wait_stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &f.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &render_done_[index];
    ctx_.submit(std::span(&submit, 1), f.in_flight, "vkQueueSubmit (frame)");

    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &render_done_[index];
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain_;
    present.pImageIndices = &index;
    const VkResult presented = ctx_.present(present);
    frame_ = (frame_ + 1) % kFramesInFlight;
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
        create_swapchain();
        return true;
    }
    check(presented, "vkQueuePresentKHR");
    return true;
}

}  // namespace echosim::gpu

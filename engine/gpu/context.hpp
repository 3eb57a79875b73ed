// The first Vulkan layer: instance, validation messenger, physical device, logical device and the
// one queue family echosim uses for graphics, compute, transfer and (in a window) presentation.
// Everything above it (resources, presenters, render passes, compute kernels) takes a Context&.
//
// Threading: recording is per thread, each recording thread with a CommandPool of its own
// (command_pool.hpp); submission goes through the context. The queue (and the device, for
// vkDeviceWaitIdle) is externally synchronised in Vulkan, so submit(), present() and wait_idle()
// are the only code that touches it, behind one mutex; they may be called from any thread. Nothing
// else on the context changes after it is made.
//
// Validation: when enabled, every warning or error the Khronos layer reports is printed and
// counted; tests assert the count stays zero.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace echosim::gpu {

struct ContextOptions {
    bool validation = false;
    std::string gpu;  // forced device name (see device_selection.hpp); empty: best available
    std::vector<std::string> instance_extensions;  // e.g. the window system's surface extensions
    // When set, only queue families for which this returns true are used (window presentation).
    std::function<bool(VkInstance, VkPhysicalDevice, std::uint32_t family)> can_present;

    // Validation on in debug builds or when ECHOSIM_VALIDATION=1; GPU from ECHOSIM_GPU.
    static ContextOptions from_environment();
};

class Context {
public:
    explicit Context(ContextOptions options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_; }
    std::uint32_t queue_family() const { return queue_family_; }
    const std::string& device_name() const { return device_name_; }
    VkPhysicalDeviceType device_type() const { return device_type_; }
    const VkPhysicalDeviceLimits& limits() const { return limits_; }
    bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }
    // Validation warnings and errors reported since the context was made. The counter outlives the
    // context, so a caller can also see what the layer reports while the device is destroyed
    // (leaked objects).
    std::uint32_t validation_messages() const { return validation_messages_->load(); }
    std::shared_ptr<const std::atomic<std::uint32_t>> validation_counter() const { return validation_messages_; }

    std::uint32_t find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags wanted) const;

    // The queue, from any thread (see the design note). Submits the batches, `fence` (or none)
    // signalled when they are done; throws std::runtime_error naming `what` when the queue refuses.
    void submit(std::span<const VkSubmitInfo> submits, VkFence fence, const char* what = "vkQueueSubmit") const;
    // Presents a swapchain image; the result is the caller's to read (out of date, suboptimal).
    VkResult present(const VkPresentInfoKHR& info) const;
    // Waits until the device has finished all work submitted so far (before GPU objects that frames
    // in flight may use are destroyed: gpu/frame.hpp). A lost device has nothing left to wait for.
    void wait_idle() const;

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                                VkDebugUtilsMessageTypeFlagsEXT types,
                                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                                void* user);
    void pick_physical_device(const ContextOptions& options);
    void create_device(bool for_window);
    void destroy();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    mutable std::mutex queue_mutex_;  // held around every use of queue_ and vkDeviceWaitIdle
    std::uint32_t queue_family_ = 0;
    std::string device_name_;
    VkPhysicalDeviceType device_type_ = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    VkPhysicalDeviceLimits limits_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    std::shared_ptr<std::atomic<std::uint32_t>> validation_messages_ = std::make_shared<std::atomic<std::uint32_t>>(0);
};

}  // namespace echosim::gpu

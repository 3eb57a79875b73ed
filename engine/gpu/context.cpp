#include "gpu/context.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#endif

#include "gpu/device_selection.hpp"
#include "gpu/vk_error.hpp"

namespace echosim::gpu {
namespace {

// In AddressSanitizer builds only: Mesa's lavapipe and the validation layer keep a few small
// allocations (128-240 bytes) in static state they never free. The Vulkan loader unloads them at
// vkDestroyInstance, after which LeakSanitizer reports those bytes from "<unknown module>", where no
// suppression can name them. Loaded once more with RTLD_NODELETE, they stay for the process's life,
// and tests/sanitizers/lsan.supp names them. A library that is not there is simply not loaded.
void keep_vulkan_drivers_loaded()
{
#if defined(__SANITIZE_ADDRESS__)
    for (const char* library : {"libvulkan_lvp.so", "libVkLayer_khronos_validation.so"}) dlopen(library, RTLD_NOW | RTLD_NODELETE);
#endif
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool env_flag(const char* name)
{
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

bool has_layer(const char* name)
{
    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(void* user, PFN_vkDebugUtilsMessengerCallbackEXT callback)
{
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = callback;
    info.pUserData = user;
    return info;
}

}  // namespace

ContextOptions ContextOptions::from_environment()
{
    ContextOptions o;
#ifndef NDEBUG
    o.validation = true;
#endif
    if (env_flag("ECHOSIM_VALIDATION")) o.validation = true;
    if (const char* gpu = std::getenv("ECHOSIM_GPU")) o.gpu = gpu;
    return o;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                              VkDebugUtilsMessageTypeFlagsEXT,
                                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                              void* user)
{
    auto* self = static_cast<Context*>(user);
    self->validation_messages_->fetch_add(1);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::fprintf(stderr, "echosim: vulkan validation %s: %s\n", level, data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

Context::Context(ContextOptions options)
{
    keep_vulkan_drivers_loaded();
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "echosim";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "echosim";
    app.apiVersion = VK_API_VERSION_1_3;

    std::vector<const char*> extensions;
    for (const auto& e : options.instance_extensions) extensions.push_back(e.c_str());
    std::vector<const char*> layers;
    auto debug_info = messenger_info(this, &Context::on_validation_message);
    if (options.validation) {
        if (!has_layer(kValidationLayer))
            throw std::runtime_error(std::string("Vulkan validation requested but ") + kValidationLayer +
                                     " is not installed (Debian package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = std::uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = std::uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    // the messenger in pNext also reports on instance creation and destruction
    if (options.validation) info.pNext = &debug_info;
    check(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");

    try {
        if (options.validation) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            if (!create) throw std::runtime_error("vkCreateDebugUtilsMessengerEXT not available");
            check(create(instance_, &debug_info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
        }
        pick_physical_device(options);
        create_device(bool(options.can_present));
    } catch (...) {
        destroy();
        throw;
    }
}

Context::~Context() { destroy(); }

void Context::destroy()
{
    if (device_) {
        wait_idle();
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy_messenger) destroy_messenger(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

void Context::pick_physical_device(const ContextOptions& options)
{
    std::uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance_, &count, devices.data()), "vkEnumeratePhysicalDevices");

    std::vector<PhysicalDeviceInfo> infos;
    std::vector<std::uint32_t> families;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);
        PhysicalDeviceInfo info;
        info.name = props.deviceName;
        info.type = props.deviceType;
        info.api_version = props.apiVersion;

        std::uint32_t nfam = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &nfam, nullptr);
        std::vector<VkQueueFamilyProperties> fams(nfam);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &nfam, fams.data());
        std::uint32_t chosen = UINT32_MAX;
        bool any_graphics = false;
        for (std::uint32_t f = 0; f < nfam && chosen == UINT32_MAX; ++f) {
            const auto need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((fams[f].queueFlags & need) != need) continue;
            any_graphics = true;
            if (!options.can_present || options.can_present(instance_, pd, f)) chosen = f;
        }
        info.has_graphics_compute_queue = any_graphics;
        info.can_present = chosen != UINT32_MAX || !any_graphics;
        infos.push_back(info);
        families.push_back(chosen);
    }

    const std::size_t i = select_physical_device(infos, options.gpu);
    physical_device_ = devices[i];
    queue_family_ = families[i];
    device_name_ = infos[i].name;
    device_type_ = infos[i].type;
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical_device_, &props);
    limits_ = props.limits;
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);
}

void Context::create_device(bool for_window)
{
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;

    // Vulkan 1.3 core: dynamic rendering and synchronization2 keep the passes free of render pass
    // objects, so offscreen targets and swapchain images are drawn by the same code.
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supported.pNext = &v13;
    vkGetPhysicalDeviceFeatures2(physical_device_, &supported);
    if (!v13.dynamicRendering || !v13.synchronization2)
        throw std::runtime_error("Vulkan device '" + device_name_ + "' lacks dynamicRendering or synchronization2");

    VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    enable13.dynamicRendering = VK_TRUE;
    enable13.synchronization2 = VK_TRUE;
    // Vulkan 1.2 core (required there): imageless framebuffers, so a pass that needs a render pass
    // object (Dear ImGui's Vulkan back-end: ui/ui_pass.hpp) keeps one framebuffer per extent and is
    // handed each frame's view when it begins, never holding a swapchain view that a resize destroys
    VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    enable12.imagelessFramebuffer = VK_TRUE;
    enable13.pNext = &enable12;

    // the swapchain only for a window (it needs the instance's surface extensions)
    std::vector<const char*> extensions;
    if (for_window) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &enable13;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = std::uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    check(vkCreateDevice(physical_device_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

std::uint32_t Context::find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags wanted) const
{
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    throw std::runtime_error("no Vulkan memory type with the wanted properties on " + device_name_);
}

void Context::submit(std::span<const VkSubmitInfo> submits, VkFence fence, const char* what) const
{
    VkResult result;
    {
        const std::lock_guard lock(queue_mutex_);
        result = vkQueueSubmit(queue_, std::uint32_t(submits.size()), submits.data(), fence);
    }
    check(result, what);
}

VkResult Context::present(const VkPresentInfoKHR& info) const
{
    const std::lock_guard lock(queue_mutex_);
    return vkQueuePresentKHR(queue_, &info);
}

void Context::wait_idle() const
{
    const std::lock_guard lock(queue_mutex_);
    vkDeviceWaitIdle(device_);
}

}  // namespace echosim::gpu

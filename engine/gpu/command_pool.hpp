// A command pool and the one thread that records into it. Vulkan command pools are externally
// synchronised, so every recording thread (the render thread, an upload thread, a test) owns one
// pool and passes it down to whatever records or uploads on its behalf (the presenters, the passes'
// uploads); nothing here is global or thread_local, and a pool is never shared between threads.
// Submission goes through the Context, which guards the queue for all threads (context.hpp).
//
// Besides handing out command buffers for per-frame recording (the window presenter), a pool
// submits one-shot work and waits for it: start-up uploads, tests, and the offscreen presenter's
// frames (each waited for by design: its image is read back); never a window's frames.
#pragma once

#include <functional>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"

namespace echosim::gpu {

class CommandPool {
public:
    explicit CommandPool(const Context& ctx);
    ~CommandPool();
    CommandPool(const CommandPool&) = delete;
    CommandPool& operator=(const CommandPool&) = delete;

    const Context& context() const { return ctx_; }
    VkCommandPool handle() const { return pool_; }
    // A primary command buffer that can be reset and re-recorded; freed with the pool, or before
    // by free() (the GPU done with it).
    VkCommandBuffer allocate();
    void free(VkCommandBuffer cmd);
    // Records `record` into the pool's one-shot command buffer, submits it and waits for the GPU.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

private:
    const Context& ctx_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer once_ = VK_NULL_HANDLE;  // reused by submit_and_wait
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace echosim::gpu

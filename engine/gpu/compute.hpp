// The compute layer: a compute pipeline over storage buffers and push constants, dispatched on the
// Context's queue. Each kernel in compute/ has a bindings header shared with C++ and a CPU
// reference of the same maths (engine/echo/), so tests can run both and compare.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/resources.hpp"

namespace echosim::gpu {

class ComputeKernel {
public:
    // `storage_buffers` bindings 0..n-1 are storage buffers; `push_bytes` of push constants.
    ComputeKernel(const Context& ctx, std::span<const std::uint32_t> spirv, const char* name, std::uint32_t storage_buffers,
                  std::uint32_t push_bytes);
    ~ComputeKernel();
    ComputeKernel(const ComputeKernel&) = delete;
    ComputeKernel& operator=(const ComputeKernel&) = delete;

    // Points the kernel's bindings at these buffers (binding i = buffers[i]); do it between
    // dispatches, never while one that uses the old bindings is in flight.
    void bind(std::span<const Buffer* const> buffers);
    // Records a dispatch of `groups` workgroups along x into `cmd`.
    void record(VkCommandBuffer cmd, std::span<const std::byte> push, std::uint32_t groups) const;

private:
    void destroy();
    const Context& ctx_;
    const char* name_;
    std::uint32_t storage_buffers_;
    std::uint32_t push_bytes_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace echosim::gpu

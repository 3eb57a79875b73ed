// The compute layer: a compute pipeline over one descriptor set of declared bindings (storage and
// uniform buffers, storage images, images with samplers) and push constants, dispatched in 1, 2 or
// 3 dimensions on the Context's queue. Each kernel in compute/ has a bindings header shared with C++
// and a CPU reference of the same maths, so tests can run both and compare.
//
// Frame slots: a kernel holds one descriptor set per frame slot (kFramesInFlight), so the frame
// being recorded can point its bindings at its own resources while the GPU still runs the other
// slot's dispatch. Bind a slot only when the GPU is done with that slot's last dispatch: at set-up,
// or from inside the record() of the pass that dispatches it, for that frame's slot (frame.hpp).
//
// Lifetime: the destructor waits for the device (Context::wait_idle) before it destroys the
// pipeline and the descriptor sets, which frames in flight may still use (frame.hpp).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/descriptors.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"

namespace echosim::gpu {

// Workgroups of a dispatch along x, y and z.
struct Groups {
    std::uint32_t x = 1, y = 1, z = 1;
    // The fewest groups of `group` invocations each that cover `items` (the kernel skips the rest).
    static Groups cover(std::uint32_t items, std::uint32_t group);
    static Groups cover(VkExtent2D items, VkExtent2D group);
    static Groups cover(VkExtent3D items, VkExtent3D group);
};

class ComputeKernel {
public:
    // `bindings[i]` is the kind of binding i; `push_bytes` of push constants. `spirv` must outlive
    // the kernel (the embedded shaders do): variants are made from it later.
    ComputeKernel(const Context& ctx, std::span<const std::uint32_t> spirv, const char* name,
                  std::span<const BindingKind> bindings, std::uint32_t push_bytes);
    ComputeKernel(const Context& ctx, std::span<const std::uint32_t> spirv, const char* name,
                  std::initializer_list<BindingKind> bindings, std::uint32_t push_bytes)
        : ComputeKernel(ctx, spirv, name, std::span(bindings.begin(), bindings.size()), push_bytes)
    {
    }
    ~ComputeKernel();
    ComputeKernel(const ComputeKernel&) = delete;
    ComputeKernel& operator=(const ComputeKernel&) = delete;

    // Points slot `slot`'s bindings at these resources (binding i = resources[i], of the declared
    // kind); throws on a wrong slot, count or kind. At set-up, or from the record() of the pass
    // that dispatches the kernel, for the slot being recorded (SlotDescriptors::bind). A kernel
    // with no bindings needs no bind.
    void bind(int slot, std::span<const Binding> resources) { descriptors_.bind(slot, resources); }
    void bind(int slot, std::initializer_list<Binding> resources) { bind(slot, std::span(resources.begin(), resources.size())); }
    // Records a dispatch of `groups` workgroups with slot `slot`'s bindings into `cmd`. Barriers
    // around it (what it reads was written, what it writes is read next) are the caller's.
    // `variant` is the value of the kernel's specialization constant 0 (constant_id = 0), for
    // kernels whose optional work must cost nothing when it is off: llvmpipe runs both sides of a
    // branch under a lane mask, so an output switched off by a uniform flag still costs its stores'
    // per-lane loops, where a constant removes them. Each variant's pipeline is made the first
    // time it is recorded (a kernel is recorded from one thread at a time).
    void record(VkCommandBuffer cmd, int slot, std::span<const std::byte> push, Groups groups, std::uint32_t variant = 0) const;
    // Makes variant `value`'s pipeline now, so its first record() does not pay for it (a frame's
    // worth of time on lavapipe, which compiles the shader then).
    void prepare(std::uint32_t value) const { variant(value); }

private:
    const Context& ctx_;
    const char* name_;
    std::uint32_t push_bytes_;
    SlotDescriptors descriptors_;
    Pipeline pipeline_;  // variant 0, and the layout of all: on descriptors_' layout, declared after it
    std::span<const std::uint32_t> spirv_;  // the embedded code, for the other variants
    struct Variant {
        std::uint32_t value;
        VkPipeline pipeline;
    };
    mutable std::vector<Variant> variants_;  // made on first use; destroyed with the kernel
    VkPipeline variant(std::uint32_t value) const;
};

}  // namespace echosim::gpu

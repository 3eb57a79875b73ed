// B-mode synthesis on the GPU: the kernels compute/bmode_scatter.comp, bmode_beam.comp,
// bmode_axial.comp and bmode_lateral.comp (bmode_bindings.h) over a tissue-label volume held on the device, frames of a
// sweep in batches (one submit each: the four passes over every frame of the batch, then one wait),
// so a case's sweep costs a few dozen submits. The CPU twin it must agree with is
// echo::synthesize(labels, ...) (engine/echo/bmode.hpp); tests/image/bmode_gpu_test.cpp compares.
//
// Memory per frame of a batch: 26 bytes a pixel on the device (buffers A and B, codes; grey,
// tissue codes and, for synthesize(), the envelope in host-visible memory read directly).
//
// Threading: one thread at a time, the one owning `pool` (gpu/command_pool.hpp).
// Lifetime: the kernels wait for the device before they go, and are declared last, so they go first.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "bmode_bindings.h"
#include "echo/sweep.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/compute.hpp"
#include "gpu/resources.hpp"
#include "io/nrrd.hpp"

namespace echosim::image {

class BModeGpu : public echo::SweepImager {
public:
    // The label volume (uint8 tissue codes, echo::voxelise_frames) uploaded once; frames of `spec`.
    // `batch`: frames per submit (0: as many as 64 MiB of batch buffers hold, up to
    // BMODE_MAX_FRAMES). Throws std::invalid_argument (a spec or volume the kernels cannot take)
    // or gpu::VulkanError (what the device cannot hold), naming it.
    BModeGpu(gpu::CommandPool& pool, const io::Volume& labels, const echo::ScanSpec& spec, std::uint32_t batch = 0);

    std::size_t batch_frames() const override { return batch_; }
    // Any number of frames, a batch per submit, each waited for.
    void image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels) override;
    std::string backend() const override;
    // One frame with its envelope (before log compression), as echo::synthesize gives it.
    echo::BModeImage synthesize(const Pose& pose);

private:
    void run_batch(std::span<const Pose> poses, bool envelope);
    gpu::CommandPool& pool_;
    kernels::BModeParams params_;
    std::uint32_t batch_ = 1;
    gpu::Buffer volume_;
    gpu::TexelView volume_texels_;
    gpu::Buffer params_buffer_, frames_buffer_;  // uniform, host-visible
    gpu::Buffer field_, labels_, beam_buffer_;    // device-local: buffers A, codes, B (bmode_bindings.h)
    gpu::TexelView field_texels_, label_texels_, beam_texels_;
    gpu::Buffer grey_, label_out_, envelope_;     // host-visible: read directly after the wait
    // last, so destroyed first: they wait for the device before the buffers they bind go
    gpu::ComputeKernel scatter_, beam_, axial_, lateral_;
};

}  // namespace echosim::image

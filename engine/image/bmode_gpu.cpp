#include "image/bmode_gpu.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "echosim_compute_shaders.hpp"

namespace echosim::image {
namespace {

constexpr int kSlot = 0;  // every batch is waited for, so one slot serves
constexpr std::uint64_t kBatchBytes = std::uint64_t(64) << 20;

static_assert(BMODE_PARAMS_BINDING == 0 && BMODE_FRAMES_BINDING == 1 && BMODE_VOLUME_BINDING == 2 && BMODE_FIELD_BINDING == 3 &&
                  BMODE_LABELS_BINDING == 4 && BMODE_BEAM_BINDING == 5 && BMODE_BEAM_TEXELS_BINDING == 6 && BMODE_GREY_BINDING == 7 &&
                  BMODE_LABEL_OUT_BINDING == 8 && BMODE_ENVELOPE_BINDING == 9 && BMODE_FIELD_TEXELS_BINDING == 10 &&
                  BMODE_LABEL_TEXELS_BINDING == 11,
              "bindings in the order declared below");
// the four kernels share one layout: each reads the bindings it declares
using gpu::BindingKind;
constexpr BindingKind kBindings[] = {BindingKind::uniform_buffer, BindingKind::uniform_buffer, BindingKind::texel_buffer,
                                     BindingKind::storage_buffer, BindingKind::storage_buffer, BindingKind::storage_buffer,
                                     BindingKind::texel_buffer,   BindingKind::storage_buffer, BindingKind::storage_buffer,
                                     BindingKind::storage_buffer, BindingKind::texel_buffer,   BindingKind::texel_buffer};

std::uint32_t pick_batch(const gpu::Context& ctx, const kernels::BModeParams& k, std::uint32_t asked)
{
    const std::uint64_t pixels = std::uint64_t(k.columns) * k.rows;
    std::uint64_t batch = asked ? asked : std::max<std::uint64_t>(1, kBatchBytes / (pixels * 26));
    // the passes read their inputs as texel buffers: all of a batch's pixels addressable
    batch = std::min<std::uint64_t>({batch, BMODE_MAX_FRAMES, std::max<std::uint64_t>(1, ctx.limits().maxTexelBufferElements / pixels)});
    return std::uint32_t(batch);
}

}  // namespace

BModeGpu::BModeGpu(gpu::CommandPool& pool, const io::Volume& labels, const echo::ScanSpec& spec, std::uint32_t batch)
    : pool_(pool),
      params_(echo::bmode_params(spec, labels)),
      batch_(pick_batch(pool.context(), params_, batch)),
      volume_(gpu::upload_buffer(pool, std::as_bytes(std::span(labels.data)), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT)),
      volume_texels_(pool.context(), volume_, VK_FORMAT_R8_UINT, "the B-mode label volume"),
      scatter_(pool.context(), kernels::bmode_scatter_comp, "bmode_scatter.comp", kBindings, 0),
      beam_(pool.context(), kernels::bmode_beam_comp, "bmode_beam.comp", kBindings, 0),
      axial_(pool.context(), kernels::bmode_axial_comp, "bmode_axial.comp", kBindings, 0),
      lateral_(pool.context(), kernels::bmode_lateral_comp, "bmode_lateral.comp", kBindings, 0)
{
    const gpu::Context& ctx = pool.context();
    const VkDeviceSize pixels = VkDeviceSize(params_.columns) * params_.rows * batch_;
    const VkDeviceSize words = VkDeviceSize(params_.row_words) * params_.rows * batch_;
    constexpr auto storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    params_buffer_ = gpu::Buffer(ctx, sizeof(kernels::BModeParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
    frames_buffer_ = gpu::Buffer(ctx, sizeof(kernels::BModeFrames), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
    constexpr auto storage_and_texels = storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    field_ = gpu::Buffer(ctx, pixels * 8, storage_and_texels, gpu::MemoryUse::device_local);
    labels_ = gpu::Buffer(ctx, pixels * 4, storage_and_texels, gpu::MemoryUse::device_local);
    beam_buffer_ = gpu::Buffer(ctx, pixels * 8, storage_and_texels, gpu::MemoryUse::device_local);
    field_texels_ = gpu::TexelView(ctx, field_, VK_FORMAT_R32G32_SFLOAT, "the B-mode field (buffer A)");
    label_texels_ = gpu::TexelView(ctx, labels_, VK_FORMAT_R32_UINT, "the B-mode frames' tissue codes");
    beam_texels_ = gpu::TexelView(ctx, beam_buffer_, VK_FORMAT_R32G32_SFLOAT, "the B-mode field down the beam (buffer B)");
    grey_ = gpu::Buffer(ctx, words * 4, storage, gpu::MemoryUse::host_visible);
    label_out_ = gpu::Buffer(ctx, words * 4, storage, gpu::MemoryUse::host_visible);
    envelope_ = gpu::Buffer(ctx, pixels * 4, storage, gpu::MemoryUse::host_visible);
    params_buffer_.write(std::as_bytes(std::span(&params_, 1)));
    const gpu::Binding bindings[] = {gpu::Binding::uniform(params_buffer_), gpu::Binding::uniform(frames_buffer_),
                                     gpu::Binding::texel(volume_texels_),   gpu::Binding::storage(field_),
                                     gpu::Binding::storage(labels_),        gpu::Binding::storage(beam_buffer_),
                                     gpu::Binding::texel(beam_texels_),     gpu::Binding::storage(grey_),
                                     gpu::Binding::storage(label_out_),     gpu::Binding::storage(envelope_),
                                     gpu::Binding::texel(field_texels_),    gpu::Binding::texel(label_texels_)};
    for (gpu::ComputeKernel* k : {&scatter_, &beam_, &axial_, &lateral_}) k->bind(kSlot, bindings);
    lateral_.prepare(BMODE_WITH_ENVELOPE);
}

std::string BModeGpu::backend() const { return pool_.context().device_name(); }

void BModeGpu::run_batch(std::span<const Pose> poses, bool envelope)
{
    kernels::BModeFrames frames{};
    for (std::size_t f = 0; f < poses.size(); ++f) frames.frame[f] = echo::bmode_pose(poses[f]);
    frames_buffer_.write(std::as_bytes(std::span(&frames, 1)));
    const std::uint32_t n = std::uint32_t(poses.size());
    pool_.submit_and_wait([&](VkCommandBuffer cmd) {
        const auto after = [&](VkAccessFlags2 read) {
            gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, read);
        };
        const VkExtent3D pixels{params_.columns, params_.rows, n};
        scatter_.record(cmd, kSlot, {}, gpu::Groups::cover(pixels, VkExtent3D{BMODE_SCATTER_GROUP_X, BMODE_SCATTER_GROUP_Y, 1}));
        after(VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        beam_.record(cmd, kSlot, {}, gpu::Groups::cover(VkExtent2D{params_.columns, n}, VkExtent2D{BMODE_BEAM_GROUP, 1}));
        after(VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        axial_.record(cmd, kSlot, {}, gpu::Groups::cover(VkExtent3D{params_.columns, (params_.rows + 3) / 4, n}, VkExtent3D{BMODE_AXIAL_GROUP_X, BMODE_AXIAL_GROUP_Y, 1}));
        after(VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        lateral_.record(cmd, kSlot, {}, gpu::Groups::cover(VkExtent3D{params_.row_words, params_.rows, n}, VkExtent3D{BMODE_LATERAL_GROUP_X, BMODE_LATERAL_GROUP_Y, 1}),
                        envelope ? BMODE_WITH_ENVELOPE : 0u);
        gpu::host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    });
}

void BModeGpu::image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels)
{
    const std::size_t columns = params_.columns, rows = params_.rows, frame_bytes = columns * rows, row_bytes = params_.row_words * 4u;
    for (std::size_t f0 = 0; f0 < poses.size(); f0 += batch_) {
        const std::size_t n = std::min<std::size_t>(batch_, poses.size() - f0);
        run_batch(poses.subspan(f0, n), false);
        // rows packed a word per 4 pixels: each row's first `columns` bytes
        const auto* grey = static_cast<const std::uint8_t*>(grey_.mapped());
        const auto* codes = static_cast<const std::uint8_t*>(label_out_.mapped());
        for (std::size_t r = 0; r < n * rows; ++r) {
            std::memcpy(pixels + f0 * frame_bytes + r * columns, grey + r * row_bytes, columns);
            std::memcpy(labels + f0 * frame_bytes + r * columns, codes + r * row_bytes, columns);
        }
    }
}

echo::BModeImage BModeGpu::synthesize(const Pose& pose)
{
    echo::BModeImage img;
    img.width = params_.columns;
    img.height = params_.rows;
    const std::size_t n = std::size_t(img.width) * img.height;
    img.pixels.resize(n);
    img.labels.resize(n);
    run_batch(std::span(&pose, 1), true);
    const std::size_t row_bytes = params_.row_words * 4u;
    for (std::size_t r = 0; r < img.height; ++r) {
        std::memcpy(img.pixels.data() + r * img.width, static_cast<const std::uint8_t*>(grey_.mapped()) + r * row_bytes, img.width);
        std::memcpy(img.labels.data() + r * img.width, static_cast<const std::uint8_t*>(label_out_.mapped()) + r * row_bytes, img.width);
    }
    img.envelope.resize(n);
    std::memcpy(img.envelope.data(), envelope_.mapped(), n * sizeof(float));
    return img;
}

}  // namespace echosim::image

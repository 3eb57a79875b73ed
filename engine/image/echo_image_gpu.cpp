#include "image/echo_image_gpu.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "echo/bmode.hpp"
#include "echo/echo_image_cpu.hpp"
#include "echosim_compute_shaders.hpp"

namespace echosim::image {
namespace {

constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// A sampled 3-D image of `extent` texels, uploaded; extent_of(v) gives a volume's own grid.
gpu::Image volume_image(gpu::CommandPool& pool, VkExtent3D extent, VkFormat format, std::span<const std::byte> texels)
{
    gpu::Image image(pool.context(), extent, format, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    gpu::upload_image(pool, image, texels, kRead);
    return image;
}

VkExtent3D extent_of(const io::Volume& v) { return {std::uint32_t(v.size[0]), std::uint32_t(v.size[1]), std::uint32_t(v.size[2])}; }

// The largest packed volume made [bytes]: four times the voxels and a little padding, in a CPU
// device's memory (the host's); beyond it the R8 volume and the trilinear sampler serve.
constexpr std::uint64_t kMaxPackedBytes = std::uint64_t(2) << 30;

// A packed volume's image (slice_bindings.h): its tiles a row, the rows of its folds between.
VkExtent3D packed_extent(const io::Volume& v)
{
    const std::uint64_t tiles = (v.size[0] + 3) / 4, rows = (v.size[1] + 3) / 4;
    const std::uint64_t height = std::min<std::uint64_t>(rows << kernels::packed_fold_bits(std::uint32_t(v.size[0])), UINT32_MAX);
    return {std::uint32_t(std::min<std::uint64_t>(tiles, SLICE_TILES_A_ROW) * 16), std::uint32_t(height), std::uint32_t(v.size[2])};
}

// The volume as slice_bindings.h's packed texels, each where packed_texel puts it: at each x, the
// grey levels of (y, z), (y + 1, z), (y, z + 1), (y + 1, z + 1), the far neighbours clamped to the
// edge. packed_texel's terms of x and of y lie in separate bits, so a texel's place is the sum of
// its x's and its (y, z)'s, each worked out once.
std::vector<std::uint32_t> pack_neighbours(const io::Volume& v)
{
    const std::size_t nx = v.size[0], ny = v.size[1], nz = v.size[2];
    const auto* g = v.as<std::uint8_t>();
    const VkExtent3D extent = packed_extent(v);
    const std::uint32_t fold_bits = kernels::packed_fold_bits(std::uint32_t(nx));
    const auto place = [&](std::size_t x, std::size_t y, std::size_t z) {
        const kernels::uvec3 t = kernels::packed_texel({std::uint32_t(x), std::uint32_t(y), std::uint32_t(z)}, fold_bits);
        return (std::size_t(t.z) * extent.height + t.y) * extent.width + t.x;
    };
    std::vector<std::uint32_t> out(std::size_t(extent.width) * extent.height * extent.depth, 0u);
    std::vector<std::size_t> along_x(nx);
    for (std::size_t x = 0; x < nx; ++x) along_x[x] = place(x, 0, 0);
    for (std::size_t z = 0; z < nz; ++z)
        for (std::size_t y = 0; y < ny; ++y) {
            const std::size_t y1 = std::min(y + 1, ny - 1), z1 = std::min(z + 1, nz - 1);
            const std::uint8_t* here = g + v.index(0, y, z);
            const std::uint8_t* below = g + v.index(0, y1, z);
            const std::uint8_t* behind = g + v.index(0, y, z1);
            const std::uint8_t* both = g + v.index(0, y1, z1);
            std::uint32_t* dst = out.data() + place(0, y, z);
            for (std::size_t x = 0; x < nx; ++x)
                dst[along_x[x]] =
                    std::uint32_t(here[x]) | std::uint32_t(below[x]) << 8 | std::uint32_t(behind[x]) << 16 | std::uint32_t(both[x]) << 24;
        }
    return out;
}

// The frame's stages as a list of sub-passes that declare what they read and write
// (gpu/stage_list.hpp), so the barriers between them are the recorder's, not each stage's:
//
//   deform: solve ─▶ deform: spread ─▶ deform: map ─▶ [B-mode: live scatter ─▶ beam ─▶ axial ─▶ lateral] ─▶ slice+post ─▶ display copy ─▶ [read-back copy]
//
// (the B-mode stages with generative imaging only). The resources are a slot's (each frame slot has
// its own); the profile, the parameters and the rows are host-written before the frame is
// submitted, so no stage declares them.
enum Resource { kSolved, kSpreadOut, kMap, kSliced, kImage, kReadback, kFieldA, kCodes, kBeamB, kGenerated };
enum StageIndex { kSolve, kSpread, kMapStage, kLiveScatter, kBeam, kAxial, kLateral, kSlice, kDisplayCopy, kReadbackCopy };

gpu::StageList frame_stages(std::uint32_t map_reads)
{
    constexpr auto compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, copy = VK_PIPELINE_STAGE_2_COPY_BIT;
    constexpr auto storage_write = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    // the deform's map pass reads the solve's outputs through texel views (a CPU device) or as storage
    const VkAccessFlags2 solved_read = map_reads != 0u ? VK_ACCESS_2_SHADER_SAMPLED_READ_BIT : VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    constexpr auto texel_read = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    return gpu::StageList(
        {{"the deform's solution (scratch, displacements, wall distances)"}, {"the displacements spread sideways"}, {"the deform map"},
         {"the sliced bytes, grey levels and labels"}, {"the displayed image", true}, {"the read-back buffer"},
         {"the B-mode field (buffer A)"}, {"the live frame's tissue codes"}, {"the B-mode field down the beam (buffer B)"},
         {"the generated grey and tissue bytes"}},
        {{"deform: solve", {}, {{kSolved, compute, storage_write}}},
         {"deform: spread", {{kSolved, compute, solved_read}}, {{kSpreadOut, compute, storage_write}}},
         {"deform: map", {{kSolved, compute, solved_read}, {kSpreadOut, compute, solved_read}}, {{kMap, compute, storage_write}}},
         {"B-mode: live scatter", {{kMap, compute, texel_read}}, {{kFieldA, compute, storage_write}, {kCodes, compute, storage_write}}},
         {"B-mode: beam", {{kFieldA, compute, texel_read}, {kCodes, compute, texel_read}}, {{kBeamB, compute, storage_write}}},
         {"B-mode: axial", {{kBeamB, compute, texel_read}}, {{kFieldA, compute, storage_write}}},
         {"B-mode: lateral", {{kFieldA, compute, texel_read}, {kCodes, compute, texel_read}}, {{kGenerated, compute, storage_write}}},
         {"slice+post", {{kMap, compute, texel_read}, {kGenerated, compute, texel_read}}, {{kSliced, compute, storage_write}}},
         {"display copy", {{kSliced, copy, VK_ACCESS_2_TRANSFER_READ_BIT}},
          {{kImage, copy, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true}}},
         {"read-back copy", {{kImage, copy, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}},
          {{kReadback, copy, VK_ACCESS_2_TRANSFER_WRITE_BIT}}}});
}

template <class T>
std::span<const std::byte> bytes_of(const T& value)
{
    return std::as_bytes(std::span(&value, 1));
}

// The B-mode kernels' one layout (bmode_bindings.h): the sweep's bindings, then the live frame's.
static_assert(BMODE_PARAMS_BINDING == 0 && BMODE_FRAMES_BINDING == 1 && BMODE_VOLUME_BINDING == 2 && BMODE_FIELD_BINDING == 3 &&
                  BMODE_LABELS_BINDING == 4 && BMODE_BEAM_BINDING == 5 && BMODE_BEAM_TEXELS_BINDING == 6 && BMODE_GREY_BINDING == 7 &&
                  BMODE_LABEL_OUT_BINDING == 8 && BMODE_ENVELOPE_BINDING == 9 && BMODE_FIELD_TEXELS_BINDING == 10 &&
                  BMODE_LABEL_TEXELS_BINDING == 11 && BMODE_LIVE_FRAME_BINDING == 12 && BMODE_LIVE_MAP_BINDING == 13,
              "B-mode bindings in the order declared below");
using gpu::BindingKind;
constexpr BindingKind kBModeBindings[] = {
    BindingKind::uniform_buffer, BindingKind::uniform_buffer, BindingKind::texel_buffer,   BindingKind::storage_buffer,
    BindingKind::storage_buffer, BindingKind::storage_buffer, BindingKind::texel_buffer,   BindingKind::storage_buffer,
    BindingKind::storage_buffer, BindingKind::storage_buffer, BindingKind::texel_buffer,   BindingKind::texel_buffer,
    BindingKind::uniform_buffer, BindingKind::texel_buffer};
std::unique_ptr<gpu::ComputeKernel> bmode_kernel(const gpu::Context& ctx, std::span<const std::uint32_t> spirv, const char* name)
{
    return std::make_unique<gpu::ComputeKernel>(ctx, spirv, name, kBModeBindings, 0);
}

}  // namespace

EchoVolumeGpu::EchoVolumeGpu(gpu::CommandPool& pool, const io::Volume& volume, const io::Volume* labels, GreyLayout layout,
                             LabelTexels label_texels)
    : labelled_(labels != nullptr),
      linear_(pool.context(), gpu::Filter::linear),
      nearest_(pool.context(), gpu::Filter::nearest)
{
    echo::check_volumes(volume, labels);
    grid_.size = volume.size;
    grid_.directions = volume.directions;
    grid_.origin = volume.origin;
    const VkExtent3D extent = packed_extent(volume);
    const std::uint32_t max_extent = pool.context().limits().maxImageDimension3D;
    const bool packable = std::uint64_t(extent.width) * extent.height * extent.depth * 4 <= kMaxPackedBytes && extent.width <= max_extent &&
                          extent.height <= max_extent && extent.depth <= max_extent;
    if (layout == GreyLayout::packed && !packable)
        throw std::invalid_argument("volume of " + std::to_string(volume.size[0]) + " x " + std::to_string(volume.size[1]) + " x " +
                                    std::to_string(volume.size[2]) + " voxels: too large to pack for this device (its image " +
                                    std::to_string(extent.width) + " x " + std::to_string(extent.height) + " x " +
                                    std::to_string(extent.depth) + ", at most " + std::to_string(max_extent) + " a side and " +
                                    std::to_string(kMaxPackedBytes >> 20) + " MiB)");
    packed_ = layout == GreyLayout::packed ||
              (layout == GreyLayout::best && pool.context().device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU && packable);
    if (packed_) {
        const std::vector<std::uint32_t> texels = pack_neighbours(volume);
        grey_ = volume_image(pool, extent, VK_FORMAT_R8G8B8A8_UNORM, std::as_bytes(std::span(texels)));
    } else {
        grey_ = volume_image(pool, extent_of(volume), VK_FORMAT_R8_UNORM, std::as_bytes(std::span(volume.data)));
    }
    if (labels && label_texels == LabelTexels::make) {
        const std::uint64_t limit = pool.context().limits().maxTexelBufferElements;
        if (labels->voxel_count() > limit)
            throw std::invalid_argument("labels of " + std::to_string(labels->voxel_count()) + " voxels: more than this device's texel buffers hold (" +
                                        std::to_string(limit) + "), which generative imaging reads them from");
        label_buffer_ = gpu::upload_buffer(pool, std::as_bytes(std::span(labels->data)), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        label_texels_ = gpu::TexelView(pool.context(), label_buffer_, VK_FORMAT_R8_UINT, "the labels as texels");
    }
    if (labels) {
        labels_ = volume_image(pool, extent_of(*labels), VK_FORMAT_R8_UINT, std::as_bytes(std::span(labels->data)));
    } else {
        io::Volume none = io::make_volume({1, 1, 1}, io::VoxelType::uint8);
        labels_ = volume_image(pool, extent_of(none), VK_FORMAT_R8_UINT, std::as_bytes(std::span(none.data)));
    }
}

namespace {

// The deform walk's steps the scratch must hold: the most over the depths the pipeline may be set
// to (set_depth_mm), its rows kept. A step is no finer than a pixel, so the most is at one end of
// the range (a deeper image walks further; one with coarser pixels than the labels, in larger steps).
std::uint32_t deepest_walk(const io::Volume& grid, const echo::ImagePlane& plane)
{
    std::uint32_t most = 0;
    for (const double depth : {plane.depth_mm, kLinearProbe.image_depth_min_mm, kLinearProbe.image_depth_max_mm}) {
        echo::ImagePlane p = plane;
        p.depth_mm = depth;
        most = std::max(most, echo::deform_max_steps(grid, p));
    }
    return most;
}

}  // namespace

EchoImageGpu::EchoImageGpu(const gpu::Context& ctx, std::shared_ptr<const EchoVolumeGpu> volume, const echo::ImagePlane& plane,
                           const echo::PatientCase& patient, DeformReads reads, echo::Imaging imaging)
    : imaging_(imaging),
      volume_(std::move(volume)),
      plane_(plane),
      initial_depth_mm_(plane.depth_mm),
      patient_(patient),
      max_steps_((echo::check_plane(plane), deepest_walk(volume_->grid(), plane))),
      map_columns_(echo::deform_columns(volume_->grid(), plane)),
      map_reads_(reads == DeformReads::texels || (reads == DeformReads::best && ctx.device_type() == VK_PHYSICAL_DEVICE_TYPE_CPU)
                     ? DEFORM_TEXEL_READS
                     : 0u),
      stages_(frame_stages(map_reads_)),
      tissues_(ctx, sizeof(echo::TissueTable), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible),
      deform_(ctx, kernels::deform_comp, "deform.comp",
              {gpu::BindingKind::sampled_image, gpu::BindingKind::storage_buffer, gpu::BindingKind::uniform_buffer,
               gpu::BindingKind::storage_buffer, gpu::BindingKind::storage_buffer, gpu::BindingKind::storage_buffer,
               gpu::BindingKind::storage_buffer, gpu::BindingKind::texel_buffer, gpu::BindingKind::texel_buffer,
               gpu::BindingKind::texel_buffer, gpu::BindingKind::storage_buffer},
              sizeof(kernels::DeformParams)),
      slice_(ctx, kernels::slice_comp, "slice.comp",
             {gpu::BindingKind::sampled_image, gpu::BindingKind::sampled_image, gpu::BindingKind::texel_buffer,
              gpu::BindingKind::storage_buffer, gpu::BindingKind::storage_buffer, gpu::BindingKind::storage_buffer,
              gpu::BindingKind::uniform_buffer, gpu::BindingKind::texel_buffer, gpu::BindingKind::texel_buffer},
             0)
{
    const bool generative = imaging_ == echo::Imaging::generative;
    if (generative && !volume_->labelled())
        throw std::invalid_argument("generative imaging needs the case's tissue labels, and this volume has none");
    if (generative && !volume_->has_label_texels())
        throw std::invalid_argument("generative imaging reads the labels as texels: make the volume with LabelTexels::make");
    static_assert(DEFORM_LABELS_BINDING == 0 && DEFORM_PROFILE_BINDING == 1 && DEFORM_TISSUES_BINDING == 2 && DEFORM_SCRATCH_BINDING == 3 &&
                      DEFORM_MAP_BINDING == 4 && DEFORM_MOVED_BINDING == 5 && DEFORM_WALLS_BINDING == 6 &&
                      DEFORM_SCRATCH_TEXELS_BINDING == 7 && DEFORM_MOVED_TEXELS_BINDING == 8 && DEFORM_WALLS_TEXELS_BINDING == 9 &&
                      DEFORM_SPREAD_BINDING == 10,
                  "deform bindings in the order declared above");
    static_assert(SLICE_VOLUME_BINDING == 0 && SLICE_LABELS_BINDING == 1 && SLICE_MAP_BINDING == 2 && SLICE_GREY_BINDING == 3 &&
                      SLICE_LABEL_OUT_BINDING == 4 && SLICE_DISPLAY_BINDING == 5 && SLICE_FRAME_BINDING == 6 && SLICE_ROWS_BINDING == 7 &&
                      SLICE_GENERATED_BINDING == 8,
                  "slice bindings in the order declared above");
    // the live frames' variants, pressed and not, made now rather than at the first frame of each
    const std::uint32_t live = SLICE_POST | (generative ? SLICE_GENERATED : volume_->packed() ? SLICE_PACKED : 0u);
    slice_.prepare(live);
    slice_.prepare(live | kernels::slice_warped_flags(echo::map_step(map_columns_, plane_)));
    if (generative) {
        live_ = bmode_kernel(ctx, kernels::bmode_live_comp, "bmode_live.comp");
        beam_ = bmode_kernel(ctx, kernels::bmode_beam_comp, "bmode_beam.comp");
        axial_ = bmode_kernel(ctx, kernels::bmode_axial_comp, "bmode_axial.comp");
        lateral_ = bmode_kernel(ctx, kernels::bmode_lateral_comp, "bmode_lateral.comp");
    }
    deform_.prepare(DEFORM_SOLVE);
    if (spread_pass()) deform_.prepare(DEFORM_SPREAD_PASS);
    deform_.prepare(map_variant());
    const echo::TissueTable table = volume_->labelled() ? echo::tissue_mechanics(patient_) : echo::paper_linear_mechanics();
    tissues_.write(std::as_bytes(std::span(table)));

    // the displayed bytes are sRGB-encoded grey, as R8_UNORM: the image panel passes them through
    // to echosim's targets, which hold sRGB-encoded bytes too (shaders/panel.frag)
    constexpr VkFormat display_format = VK_FORMAT_R8_UNORM;
    const VkDeviceSize pixels = plane_.pixels();
    const VkDeviceSize display_bytes = VkDeviceSize(kernels::slice_words(plane_.columns)) * 4 * plane_.rows;
    constexpr auto storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    for (int s = 0; s < gpu::kFramesInFlight; ++s) {
        Slot& slot = slots_[std::size_t(s)];
        slot.profile = gpu::Buffer(ctx, map_columns_ * sizeof(echo::ColumnProfile), storage, gpu::MemoryUse::host_visible);
        slot.params = gpu::Buffer(ctx, sizeof(kernels::SliceFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
        slot.rows = gpu::Buffer(ctx, VkDeviceSize(plane_.rows) * sizeof(kernels::PostRow), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                gpu::MemoryUse::host_visible);
        slot.row_texels = gpu::TexelView(ctx, slot.rows, VK_FORMAT_R32G32B32A32_SFLOAT, "the image rows' post parameters");
        slot.display = gpu::Buffer(ctx, display_bytes, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUse::device_local);
        // written as storage buffers by the deform's solve pass, read by its map pass as texel buffers (a CPU device) or storage
        constexpr auto storage_and_texels = storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        slot.scratch = gpu::Buffer(ctx, VkDeviceSize(map_columns_) * max_steps_ * sizeof(kernels::uvec2), storage_and_texels,
                                   gpu::MemoryUse::device_local);
        const VkDeviceSize boundaries = VkDeviceSize(map_columns_) * (max_steps_ + 1);
        slot.moved = gpu::Buffer(ctx, boundaries * sizeof(float), storage_and_texels, gpu::MemoryUse::device_local);
        slot.walls = gpu::Buffer(ctx, boundaries * sizeof(std::uint32_t), storage_and_texels, gpu::MemoryUse::device_local);
        slot.scratch_texels = gpu::TexelView(ctx, slot.scratch, VK_FORMAT_R32G32_UINT, "the deform stage's scratch");
        slot.moved_texels = gpu::TexelView(ctx, slot.moved, VK_FORMAT_R32_SFLOAT, "the deform stage's displacements");
        slot.walls_texels = gpu::TexelView(ctx, slot.walls, VK_FORMAT_R32_UINT, "the deform stage's wall distances");
        slot.spread = gpu::Buffer(ctx, (spread_pass() ? boundaries : 1) * sizeof(float), storage, gpu::MemoryUse::device_local);
        slot.map = gpu::Buffer(ctx, VkDeviceSize(map_columns_) * plane_.rows * 2 * sizeof(float),
                               storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUse::device_local);
        slot.map_texels = gpu::TexelView(ctx, slot.map, VK_FORMAT_R32G32_SFLOAT, "the deform map");
        slot.grey = gpu::Buffer(ctx, pixels * sizeof(float), storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUse::device_local);
        slot.labels = gpu::Buffer(ctx, pixels * sizeof(std::uint32_t), storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUse::device_local);
        slot.image = gpu::Image(ctx, VkExtent2D{plane_.columns, plane_.rows}, display_format,
                                VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                VK_IMAGE_ASPECT_COLOR_BIT,
                                {VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_ONE});
        deform_.bind(s, {gpu::Binding::sampled(volume_->labels(), volume_->nearest()), gpu::Binding::storage(slot.profile),
                         gpu::Binding::uniform(tissues_), gpu::Binding::storage(slot.scratch), gpu::Binding::storage(slot.map),
                         gpu::Binding::storage(slot.moved), gpu::Binding::storage(slot.walls), gpu::Binding::texel(slot.scratch_texels),
                         gpu::Binding::texel(slot.moved_texels), gpu::Binding::texel(slot.walls_texels), gpu::Binding::storage(slot.spread)});
        // the generated grey bytes, rows of whole words as the lateral pass packs them (a stand-in of one word without)
        const VkDeviceSize generated_bytes = generative ? VkDeviceSize((plane_.columns + 3) / 4) * 4 * plane_.rows : 4;
        slot.generated = gpu::Buffer(ctx, generated_bytes, storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, gpu::MemoryUse::device_local);
        slot.generated_texels = gpu::TexelView(ctx, slot.generated, VK_FORMAT_R8_UINT, "the generated image's grey bytes");
        slice_.bind(s, {gpu::Binding::sampled(volume_->grey(), volume_->linear()), gpu::Binding::sampled(volume_->labels(), volume_->nearest()),
                        gpu::Binding::texel(slot.map_texels), gpu::Binding::storage(slot.grey), gpu::Binding::storage(slot.labels),
                        gpu::Binding::storage(slot.display), gpu::Binding::uniform(slot.params), gpu::Binding::texel(slot.row_texels),
                        gpu::Binding::texel(slot.generated_texels)});
        if (!generative) continue;
        slot.live = gpu::Buffer(ctx, sizeof(kernels::BModeLiveFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
        slot.bmode_params = gpu::Buffer(ctx, sizeof(kernels::BModeParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
        slot.field = gpu::Buffer(ctx, pixels * 8, storage_and_texels, gpu::MemoryUse::device_local);
        slot.codes = gpu::Buffer(ctx, pixels * 4, storage_and_texels, gpu::MemoryUse::device_local);
        slot.beam = gpu::Buffer(ctx, pixels * 8, storage_and_texels, gpu::MemoryUse::device_local);
        slot.generated_codes = gpu::Buffer(ctx, generated_bytes, storage, gpu::MemoryUse::device_local);
        slot.field_texels = gpu::TexelView(ctx, slot.field, VK_FORMAT_R32G32_SFLOAT, "the B-mode field (buffer A)");
        slot.code_texels = gpu::TexelView(ctx, slot.codes, VK_FORMAT_R32_UINT, "the live frame's tissue codes");
        slot.beam_texels = gpu::TexelView(ctx, slot.beam, VK_FORMAT_R32G32_SFLOAT, "the B-mode field down the beam (buffer B)");
        // bindings 1 and 9 (the sweep's poses and envelope) no live pass reads: stand-ins of their kinds
        const gpu::Binding bmode[] = {gpu::Binding::uniform(slot.bmode_params), gpu::Binding::uniform(slot.live),
                                gpu::Binding::texel(volume_->label_texels()), gpu::Binding::storage(slot.field),
                                gpu::Binding::storage(slot.codes),          gpu::Binding::storage(slot.beam),
                                gpu::Binding::texel(slot.beam_texels),      gpu::Binding::storage(slot.generated),
                                gpu::Binding::storage(slot.generated_codes), gpu::Binding::storage(slot.generated_codes),
                                gpu::Binding::texel(slot.field_texels),     gpu::Binding::texel(slot.code_texels),
                                gpu::Binding::uniform(slot.live),           gpu::Binding::texel(slot.map_texels)};
        for (gpu::ComputeKernel* k : {live_.get(), beam_.get(), axial_.get(), lateral_.get()}) k->bind(s, bmode);
    }
}

void EchoImageGpu::record(VkCommandBuffer cmd, int slot_index, const echo::EchoFrame& frame, VkImageLayout final_layout, bool want_labels,
                          Stages stages)
{
    record_frame(cmd, slot_index, frame, final_layout, want_labels, false, stages);
}

void EchoImageGpu::record_frame(VkCommandBuffer cmd, int slot_index, const echo::EchoFrame& frame, VkImageLayout final_layout,
                                bool want_labels, bool want_grey, Stages stages)
{
    // first, so a frame whose profiles do not match the plane throws before anything is written
    const std::vector<echo::ColumnProfile> profiles = echo::deform_profiles(frame, plane_, map_columns_);
    Slot& slot = slots_[std::size_t(slot_index)];
    const bool warped = !frame.columns.empty();
    const bool all = stages == Stages::all;
    // the walk's steps at this depth (the scratch holds the deepest's: max_steps_)
    echo::KernelParams k = echo::make_kernel_params(volume_->grid(), plane_, frame, scanner_, patient_, volume_->labelled());
    if (want_labels && volume_->labelled()) k.slice.flags |= SLICE_LABELS;
    if (all) k.slice.flags |= SLICE_POST;
    if (volume_->packed()) k.slice.flags |= SLICE_PACKED;
    if (want_grey) k.slice.flags |= SLICE_GREY;
    // the slot's previous frame is done (the caller waited for it), so its host-visible inputs are free
    const kernels::SliceFrame params{k.slice, k.post};
    slot.params.write(bytes_of(params));
    auto* rows = static_cast<kernels::PostRow*>(slot.rows.mapped());
    for (std::uint32_t r = 0; r < plane_.rows; ++r) rows[r] = kernels::post_row(r, k.post);

    const bool generative = imaging_ == echo::Imaging::generative;
    if (generative) {
        k.slice.flags |= SLICE_GENERATED;
        k.slice.flags &= ~std::uint32_t(SLICE_PACKED);
        const kernels::BModeLiveFrame live{echo::bmode_pose(frame.face), k.slice};
        slot.live.write(bytes_of(live));
        if (slot.bmode_depth_mm != plane_.depth_mm) {  // the tables down the beam go a row a pixel: remade with the depth
            slot.bmode_params.write(bytes_of(echo::bmode_live_params(plane_)));
            slot.bmode_depth_mm = plane_.depth_mm;
        }
    }
    std::uint32_t active = 0;
    if (warped && stages != Stages::slice_only) active |= 1u << kSolve | (spread_pass() ? 1u << kSpread : 0u) | 1u << kMapStage;
    if (stages != Stages::deform_only) active |= 1u << kSlice;
    if (generative && stages != Stages::deform_only) active |= 1u << kLiveScatter | 1u << kBeam | 1u << kAxial | 1u << kLateral;
    if (all) active |= 1u << kDisplayCopy | (readback_enabled_ ? 1u << kReadbackCopy : 0u);
    std::array<VkImage, kGenerated + 1> images{};
    images[kImage] = slot.image.handle();
    // the displayed image handed on to its reader: the panel's fragment shader, or a copy
    const bool to_transfer = final_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const gpu::StageAccess reader{kImage, to_transfer ? VK_PIPELINE_STAGE_2_COPY_BIT : VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                  to_transfer ? VK_ACCESS_2_TRANSFER_READ_BIT : VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, final_layout};
    const gpu::Groups columns = gpu::Groups::cover(map_columns_, DEFORM_GROUP_SIZE);
    if (timer_) timer_->begin(cmd, slot_index);
    stages_.record(cmd, active, images, std::span(&reader, 1), [&](std::size_t stage) {
        if (timer_) timer_->mark(cmd, slot_index, stage);
        switch (stage) {
        case kSolve:  // the columns solved...
            slot.profile.write(std::as_bytes(std::span(profiles)));
            deform_.record(cmd, slot_index, bytes_of(k.deform), columns, DEFORM_SOLVE);
            break;
        case kSpread:  // ...their displacements spread sideways, a run of step boundaries an invocation...
            deform_.record(cmd, slot_index, bytes_of(k.deform),
                           gpu::Groups::cover(VkExtent2D{map_columns_, (k.deform.max_steps + DEFORM_SPREAD_RUN) / DEFORM_SPREAD_RUN},
                                              VkExtent2D{DEFORM_GROUP_SIZE, 1}),
                           DEFORM_SPREAD_PASS);
            break;
        case kMapStage:  // ...then mapped
            deform_.record(cmd, slot_index, bytes_of(k.deform), columns, map_variant());
            break;
        case kLiveScatter:
            live_->record(cmd, slot_index, {}, gpu::Groups::cover(VkExtent2D{plane_.columns, plane_.rows}, VkExtent2D{BMODE_SCATTER_GROUP_X, BMODE_SCATTER_GROUP_Y}));
            break;
        case kBeam:
            beam_->record(cmd, slot_index, {}, gpu::Groups::cover(VkExtent2D{plane_.columns, 1}, VkExtent2D{BMODE_BEAM_GROUP, 1}));
            break;
        case kAxial:
            axial_->record(cmd, slot_index, {},
                           gpu::Groups::cover(VkExtent2D{plane_.columns, (plane_.rows + 3) / 4}, VkExtent2D{BMODE_AXIAL_GROUP_X, BMODE_AXIAL_GROUP_Y}));
            break;
        case kLateral:
            lateral_->record(cmd, slot_index, {},
                             gpu::Groups::cover(VkExtent2D{(plane_.columns + 3) / 4, plane_.rows}, VkExtent2D{BMODE_LATERAL_GROUP_X, BMODE_LATERAL_GROUP_Y}));
            break;
        case kSlice: {
            const VkExtent2D runs{kernels::slice_runs(plane_.columns), plane_.rows};
            slice_.record(cmd, slot_index, {}, gpu::Groups::cover(runs, VkExtent2D{SLICE_GROUP_X, SLICE_GROUP_Y}), k.slice.flags);
            break;
        }
        case kDisplayCopy: {  // the packed bytes into the displayed image (its last contents are not needed)
            VkBufferImageCopy from_words{};
            from_words.bufferRowLength = kernels::slice_words(plane_.columns) * 4;  // bytes: R8 texels
            from_words.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            from_words.imageExtent = {plane_.columns, plane_.rows, 1};
            vkCmdCopyBufferToImage(cmd, slot.display.handle(), slot.image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &from_words);
            break;
        }
        case kReadbackCopy: {  // the live read-back: the image to the slot's host buffer, read once the slot's fence has signalled
            VkBufferImageCopy to_buffer{};
            to_buffer.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            to_buffer.imageExtent = {plane_.columns, plane_.rows, 1};
            vkCmdCopyImageToBuffer(cmd, slot.image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, slot.readback.handle(), 1, &to_buffer);
            gpu::host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            break;
        }
        }
    });
    if (timer_) timer_->end(cmd, slot_index);
}

void EchoImageGpu::enable_stage_timing(const gpu::Context& ctx)
{
    if (!timer_) timer_ = std::make_unique<gpu::StageTimer>(ctx, gpu::kFramesInFlight, stages_.size());
}

std::vector<std::pair<std::string, double>> EchoImageGpu::stage_times(int slot) const
{
    std::vector<std::pair<std::string, double>> times;
    if (!timer_) return times;
    const std::vector<double> ms = timer_->stage_ms(slot);
    for (std::size_t i = 0; i < ms.size(); ++i)
        if (ms[i] >= 0) times.emplace_back(stages_.stage(i).name, ms[i]);
    return times;
}

std::pair<double, double> EchoImageGpu::depth_range() const
{
    return {std::min(kLinearProbe.image_depth_min_mm, initial_depth_mm_), std::max(kLinearProbe.image_depth_max_mm, initial_depth_mm_)};
}

void EchoImageGpu::set_depth_mm(double depth_mm)
{
    const auto [shallowest, deepest] = depth_range();
    if (!(depth_mm >= shallowest && depth_mm <= deepest))
        throw std::invalid_argument("echographic image: depth " + std::to_string(depth_mm) + " mm is outside the " + std::to_string(shallowest) +
                                    " to " + std::to_string(deepest) + " mm this pipeline was made for");
    plane_.depth_mm = depth_mm;
}

void EchoImageGpu::enable_readback(const gpu::Context& ctx)
{
    if (readback_enabled_) return;
    for (Slot& slot : slots_)
        slot.readback = gpu::Buffer(ctx, plane_.pixels(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUse::host_visible);
    readback_enabled_ = true;
}

std::span<const std::uint8_t> EchoImageGpu::readback(int slot) const
{
    if (!readback_enabled_) return {};
    return {static_cast<const std::uint8_t*>(slots_[std::size_t(slot)].readback.mapped()), plane_.pixels()};
}

echo::EchoImage EchoImageGpu::render(gpu::CommandPool& pool, const echo::EchoFrame& frame, bool want_labels)
{
    const gpu::Context& ctx = pool.context();
    const VkDeviceSize pixels = plane_.pixels();
    const bool warped = !frame.columns.empty(), labels = want_labels && volume_->labelled();
    // one host-visible buffer takes every output back: image, grey, map, labels
    const VkDeviceSize image_bytes = pixels, grey_bytes = pixels * 4, map_bytes = warped ? slots_[0].map.size() : 0, label_bytes = labels ? pixels * 4 : 0;
    gpu::Buffer readback(ctx, image_bytes + grey_bytes + map_bytes + label_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUse::host_visible);
    const Slot& slot = slots_[0];
    pool.submit_and_wait([&](VkCommandBuffer cmd) {
        record_frame(cmd, 0, frame, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, want_labels, true, Stages::all);
        gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy to_buffer{};
        to_buffer.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        to_buffer.imageExtent = {plane_.columns, plane_.rows, 1};
        vkCmdCopyImageToBuffer(cmd, slot.image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &to_buffer);
        VkDeviceSize at = image_bytes;
        const auto copy = [&](const gpu::Buffer& from, VkDeviceSize bytes) {
            const VkBufferCopy region{0, at, bytes};
            vkCmdCopyBuffer(cmd, from.handle(), readback.handle(), 1, &region);
            at += bytes;
        };
        copy(slot.grey, grey_bytes);
        if (warped) copy(slot.map, map_bytes);
        if (labels) copy(slot.labels, label_bytes);
        gpu::host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });

    echo::EchoImage out;
    out.columns = plane_.columns;
    out.rows = plane_.rows;
    out.map_columns = map_columns_;
    const auto* bytes = static_cast<const std::byte*>(readback.mapped());
    out.rgba.resize(pixels);
    for (VkDeviceSize i = 0; i < pixels; ++i) {
        const std::uint32_t g = std::uint32_t(bytes[i]);
        out.rgba[i] = g | (g << 8) | (g << 16) | (255u << 24);
    }
    out.grey.resize(pixels);
    std::memcpy(out.grey.data(), bytes + image_bytes, grey_bytes);
    if (warped) {
        out.map.resize(map_bytes / sizeof(float));
        std::memcpy(out.map.data(), bytes + image_bytes + grey_bytes, map_bytes);
    }
    if (labels) {
        const auto* codes = reinterpret_cast<const std::uint32_t*>(bytes + image_bytes + grey_bytes + map_bytes);
        out.labels.resize(pixels);
        for (VkDeviceSize i = 0; i < pixels; ++i) out.labels[i] = std::uint8_t(codes[i]);
    }
    return out;
}

}  // namespace echosim::image

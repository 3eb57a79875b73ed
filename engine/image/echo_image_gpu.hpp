// The echographic image pipeline on the GPU (DESIGN.md §1): deform ▶ slice ▶ post, the kernels of
// compute/ (deform.comp, then slice.comp, which runs the post stage on each sample), recorded as a
// list of stages that declare what they read and write, the barriers between them placed by one
// recorder (gpu/stage_list.hpp; the list in echo_image_gpu.cpp), from a volume
// and its labels held on the GPU as 3-D images to the displayed image, with no round trip through
// host memory. Per frame the host hands over only the frame's
// small input (the probe's pose and, per image column, the skin's indentation: echo::EchoFrame).
//
// Two uses, one set of kernels:
//   - live, recorded into the window's frame by a pass before the image panel (runner/echo_image_pass:
//     record() for the frame's slot, then the panel shows image(slot));
//   - offscreen (render()): one frame, waited for and read back, for `echosim slice`, the tests
//     and the benchmark.
// The displayed image is one grey byte a pixel, sRGB-encoded (R8_UNORM, its view swizzled to grey:
// {R, R, R, 1}),
// which the slice kernel writes packed four to a word into a buffer and a copy puts into the image.
//
// Live read-back (`echosim run --igtl`, the link to 3D Slicer), only when asked for
// (enable_readback()): record() then also copies the slot's displayed image into a host-visible
// buffer of the slot, in the same command buffer, after the post stage and before the panel reads
// it. Nothing waits for it: the host reads it once the slot's fence has signalled, which the
// presenter waits for anyway before it records the slot again (kFramesInFlight frames later), so
// the pixels arrive a frame or two behind the display and the display path keeps its pace.
//
// Frame slots: every buffer a frame writes (the profile, the kernels' parameters, the scratch, the
// deform map, the grey and label images, the displayed image) exists once per slot, so the frame being recorded never
// touches what the GPU may still be reading for the other slot (gpu/frame.hpp).
//
// Lifetime: the kernels wait for the device before they go, and are declared last, so they go
// first (gpu/frame.hpp, "Lifetime").
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "echo/echo_frame.hpp"
#include "echo/kernel_params.hpp"
#include "echo/tissue_mechanics.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/compute.hpp"
#include "gpu/frame.hpp"
#include "gpu/resources.hpp"
#include "gpu/stage_list.hpp"
#include "gpu/stage_timer.hpp"
#include "io/nrrd.hpp"

namespace echosim::image {

// A volume and its labels as the kernels sample them: uint8 grey levels (UNORM8, trilinear) and
// uint8 tissue codes (nearest) on the same grid. On a CPU device (lavapipe) the grey levels are
// packed with their neighbours, four to a texel, in tiles (slice_bindings.h, SLICE_PACKED), while
// that takes at most 2 GiB and an image the device can make: four times the memory, for a slice
// about twice as fast there. Without labels a one-voxel map stands in and the
// deformation is the paper's linear one. Throws (std::invalid_argument, gpu::VulkanError) naming
// what does not fit: voxel types, grids, a size the device cannot hold.
// How the grey levels are held: as the device suits best (packed on a CPU device within the
// budget, else R8), or one of the two whatever the device (tests run both against the CPU twin).
enum class GreyLayout { best, sampler, packed };

// Whether the labels are also held as a texel buffer (x fastest), which generative imaging reads.
enum class LabelTexels { none, make };

class EchoVolumeGpu {
public:
    EchoVolumeGpu(gpu::CommandPool& pool, const io::Volume& volume, const io::Volume* labels, GreyLayout layout = GreyLayout::best,
                  LabelTexels label_texels = LabelTexels::none);

    const io::Volume& grid() const { return grid_; }  // the geometry (no voxels)
    bool labelled() const { return labelled_; }
    bool packed() const { return packed_; }  // grey() holds packed neighbours (RGBA8), not R8
    const gpu::Image& grey() const { return grey_; }
    const gpu::Image& labels() const { return labels_; }
    bool has_label_texels() const { return label_buffer_.size() > 0; }
    const gpu::TexelView& label_texels() const { return label_texels_; }  // with LabelTexels::make
    const gpu::Sampler& linear() const { return linear_; }
    const gpu::Sampler& nearest() const { return nearest_; }

private:
    io::Volume grid_;
    bool labelled_ = false;
    bool packed_ = false;
    gpu::Image grey_, labels_;
    gpu::Buffer label_buffer_;
    gpu::TexelView label_texels_;
    gpu::Sampler linear_, nearest_;
};

// Which of the frame's stages record() records: all (a live frame), the slice alone, or the deform
// stage alone (the benchmark's split of the frame's cost: the slice kernel without the post stage
// and without the copy into the displayed image, a pressed frame's slice then reading the slot's
// deform map as the slot's last full frame left it; or the deform stage's dispatches, which write
// that map and nothing else). Only `all` writes the displayed image.
enum class Stages { all, slice_only, deform_only };

// How the deform's map pass reads what its solve pass wrote (deform_bindings.h, DEFORM_TEXEL_READS):
// as the device suits best (through texel views on a CPU device, as storage on a GPU), or one of the
// two whatever the device (tests run both against the CPU twin).
enum class DeformReads { best, storage, texels };

// Generative imaging (echo::Imaging::generative) puts the B-mode model's passes between the deform
// and the post stage: the deform map says where each pixel's tissue rests, bmode_live.comp takes the
// tissue (the volume's labels) and the scatterers there, the sweep's beam, axial and lateral passes
// (bmode_bindings.h) make the image, and the slice kernel's post stage (SLICE_GENERATED) gives it the
// scanner's gain, TGC, dynamic range and markers as it gives the sliced one:
//
//   deform: solve ─▶ spread ─▶ map ─▶ B-mode: live scatter ─▶ beam ─▶ axial ─▶ lateral ─▶ slice+post ─▶ display copy
//
// The volume must be labelled; its grey levels are not read. The B-mode model's settings are
// echo::ScanSpec's defaults (the probe's), at the plane's pixels (echo::bmode_live_params).
class EchoImageGpu {
public:
    EchoImageGpu(const gpu::Context& ctx, std::shared_ptr<const EchoVolumeGpu> volume, const echo::ImagePlane& plane,
                 const echo::PatientCase& patient, DeformReads reads = DeformReads::best,
                 echo::Imaging imaging = echo::Imaging::interpolative);

    // The plane the next frames are recorded with: the one made with, at the depth set last.
    const echo::ImagePlane& plane() const { return plane_; }
    // The scanner's depth control: the frames recorded from now on reach `depth_mm` down the beam,
    // in the same rows (finer or coarser pixels), as a scanner's depth knob changes the scale. Within
    // depth_range(): kLinearProbe's image_depth_min_mm to image_depth_max_mm, and the depth made
    // with. Throws std::invalid_argument naming the depth otherwise.
    void set_depth_mm(double depth_mm);
    std::pair<double, double> depth_range() const;
    echo::Imaging imaging() const { return imaging_; }
    const io::Volume& volume_grid() const { return volume_->grid(); }  // the volume's geometry (no voxels)
    echo::ScannerSettings& scanner() { return scanner_; }

    // Records the frame's three stages into `cmd` for frame slot `slot`, leaving the slot's image in
    // `final_layout` (SHADER_READ_ONLY_OPTIMAL for the panel, visible to fragment shaders; or
    // TRANSFER_SRC_OPTIMAL for a read-back). `want_labels`: also fill the slot's label buffer.
    // `stages`: see Stages (`final_layout` is used by `all` only).
    // Throws std::invalid_argument when the frame's profile does not match the plane.
    void record(VkCommandBuffer cmd, int slot, const echo::EchoFrame& frame, VkImageLayout final_layout, bool want_labels = false,
                Stages stages = Stages::all);
    const gpu::Image& image(int slot) const { return slots_[std::size_t(slot)].image; }

    // From now on, record() also copies each frame's displayed image to the host (above).
    void enable_readback(const gpu::Context& ctx);
    bool readback_enabled() const { return readback_enabled_; }
    // The displayed image (grey bytes, row-major) the slot's last frame wrote: valid once that
    // frame's fence has signalled (when the slot is next recorded, before record()); empty while
    // read-back is off.
    std::span<const std::uint8_t> readback(int slot) const;

    // From now on, record() also writes GPU timestamps between its stages (gpu/stage_timer.hpp):
    // the benchmarks' breakdown of a frame. Throws std::runtime_error where the queue keeps none.
    void enable_stage_timing(const gpu::Context& ctx);
    // Each stage the slot's last frame ran, by name ("deform: solve", ...), with its milliseconds
    // on the GPU; valid once that frame's fence has signalled. Empty while timing is off.
    std::vector<std::pair<std::string, double>> stage_times(int slot) const;

    // One frame, offscreen: recorded in slot 0, submitted through `pool` (the calling thread's),
    // waited for, and read back with the stages' outputs (the map only when the frame presses; the
    // labels with `want_labels` and a labelled volume). Not while a window's frames use slot 0.
    echo::EchoImage render(gpu::CommandPool& pool, const echo::EchoFrame& frame, bool want_labels = false);

private:
    // record(), and render()'s: `want_grey` also fills the slot's grey buffer (the sliced levels).
    void record_frame(VkCommandBuffer cmd, int slot, const echo::EchoFrame& frame, VkImageLayout final_layout, bool want_labels,
                      bool want_grey, Stages stages);
    struct Slot {
        gpu::Buffer profile, params, rows;  // host-visible, written when the slot is recorded
        gpu::TexelView row_texels;  // rows, as the slice kernel reads them
        gpu::Buffer scratch, moved, walls, map, grey, labels;
        gpu::TexelView map_texels;  // the map as the slice kernel reads it
        gpu::Buffer spread;  // the deform's displacements spread sideways (a GPU's spread pass writes them, its map pass reads them)
        gpu::TexelView scratch_texels, moved_texels, walls_texels;  // as the deform's map pass reads them on a CPU device
        gpu::Buffer display;  // the displayed image's bytes as the slice kernel packs them
        gpu::Image image;
        gpu::Buffer readback;  // host-visible, with enable_readback()
        // generative imaging's (bmode_bindings.h): the live frame, buffers A and B, the codes, the
        // generated grey and tissue bytes; interpolative imaging: only `generated`, a stand-in
        gpu::Buffer live, field, codes, beam, generated, generated_codes;
        gpu::Buffer bmode_params;  // uniform: echo::bmode_live_params at bmode_depth_mm, remade when the depth changes
        double bmode_depth_mm = 0;
        gpu::TexelView field_texels, code_texels, beam_texels, generated_texels;
    };
    echo::Imaging imaging_;
    std::shared_ptr<const EchoVolumeGpu> volume_;
    echo::ImagePlane plane_;
    double initial_depth_mm_;
    echo::PatientCase patient_;
    echo::ScannerSettings scanner_;
    std::uint32_t max_steps_ = 0;    // the scratch's steps a column: the deepest walk of depth_range()
    std::uint32_t map_columns_ = 0;  // the deform stage's columns (echo::deform_columns)
    std::uint32_t map_reads_ = 0;    // DEFORM_TEXEL_READS or 0: the map pass's variant bit
    // the deform's spread pass runs where its buffers are read as storage (a GPU: deform_bindings.h)
    bool spread_pass() const { return map_reads_ == 0u; }
    std::uint32_t map_variant() const { return DEFORM_MAP | map_reads_ | (spread_pass() ? DEFORM_SPREAD_LOADED : 0u); }
    gpu::StageList stages_;          // the frame's stages and what each reads and writes (echo_image_gpu.cpp)
    bool readback_enabled_ = false;
    gpu::Buffer tissues_;  // uniform, written once
    std::unique_ptr<gpu::StageTimer> timer_;  // with enable_stage_timing()
    std::array<Slot, gpu::kFramesInFlight> slots_;
    // last, so destroyed first: they wait for the device before the resources they bind go
    gpu::ComputeKernel deform_, slice_;
    std::unique_ptr<gpu::ComputeKernel> live_, beam_, axial_, lateral_;  // generative imaging's
};

}  // namespace echosim::image

// B-mode image synthesis (DESIGN.md §1, "ultrasound data"): what a linear probe at a pose would
// show of a medium. The model, per image:
//   1. scatterers: each tissue scatters with its own strength; the scatterers are fixed in the
//      body (a hash of the world position on a 0.1 mm lattice), so neighbouring frames see the same
//      speckle, as a real sweep does, and a reconstructed volume can be checked against direct images;
//      the beam's elevational thickness is summed over planes one lattice step apart either side of
//      the image plane (the tissue taken from the image plane itself: an approximation only where a
//      boundary runs obliquely through the slice);
//   2. specular echoes where the tissue changes along the beam (vessel walls, fascia, bone), with
//      the reflection coefficient of the two tissues' acoustic impedances;
//   3. attenuation along the beam, tissue by tissue, less a time-gain compensation; what a strong
//      reflector (bone) does not transmit is missing below it: the acoustic shadow;
//   4. the complex (I/Q) field convolved with the point-spread function (Gaussian axially and
//      laterally), its magnitude the envelope: Rayleigh-distributed speckle where scatterers are
//      dense (envelope mean / standard deviation = 1.91);
//   5. log compression to 8 bits over the dynamic range (log_compress.hpp, the GPU kernel's maths).
// The arithmetic is compute/bmode_bindings.h's, shared with the GPU kernels (compute/bmode_*.comp,
// driven by image/bmode_gpu.hpp): the functions here are their CPU twin, in float, in the kernels'
// order. The anatomy reaches the kernels as a tissue-label volume (voxelise_frames) and the
// tissues' acoustics as tables (bmode_params), so a changed phantom flows in without shader changes.
// Image geometry (PLUS "MF"): columns along the probe's +x (lateral), rows along +y (depth); the
// pixel (i, j) centre lies at x = (i + 0.5) * pixel - width / 2, y = (j + 0.5) * pixel.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/pose.hpp"
#include "core/probe_spec.hpp"
#include "bmode_bindings.h"
#include "slice_bindings.h"
#include "echo/echo_frame.hpp"
#include "echo/phantom.hpp"
#include "io/nrrd.hpp"

namespace echosim::echo {

// What the synthesis asks of the body it images.
class Medium {
public:
    virtual ~Medium() = default;
    virtual Tissue tissue_at(const glm::dvec3& world) const = 0;
};

// The scanner's settings for one image: the probe's footprint and sound (core/probe_spec.hpp) and
// how the image is formed from it.
struct ScanSpec {
    double width_mm = kLinearProbe.face_width_mm;
    double depth_mm = kLinearProbe.image_depth_mm;
    double pixel_mm = 0.1;
    double frequency_mhz = kLinearProbe.frequency_mhz;
    double axial_fwhm_mm = 0.3;      // pulse length
    double lateral_fwhm_mm = 0.6;    // beam width at focus
    double elevational_fwhm_mm = 1.2;  // slice thickness, sampled by planes one scatterer apart
    double tgc_db_per_cm_mhz = 0.75;  // time-gain compensation, as for soft tissue (round trip applied inside)
    double dynamic_range_db = 55.0;
    double gain_db = 0.0;
    bool texture = true;             // muscle fibres and fat septa (off: plain speckle, for tests)

    std::uint32_t columns() const { return std::uint32_t(width_mm / pixel_mm + 0.5); }
    std::uint32_t rows() const { return std::uint32_t(depth_mm / pixel_mm + 0.5); }
};

struct BModeImage {
    std::uint32_t width = 0, height = 0;  // columns, rows
    std::vector<std::uint8_t> pixels;     // log-compressed grey, row-major, row 0 at the skin
    std::vector<float> envelope;          // before log compression
    std::vector<std::uint8_t> labels;     // Tissue in the image plane
};

// The one-way attenuation of a tissue in this model [dB/cm/MHz] (the image's deform stage needs it
// to take away the posterior enhancement behind a lumen that closes).
double attenuation_db_cm_mhz(Tissue t);

// The image at `probe`, the tissue of each pixel asked of `medium` directly.
BModeImage synthesize(const Medium& medium, const Pose& probe, const ScanSpec& spec);

// The kernels' fixed parameters for `spec` (the tissues' acoustic tables, the point-spread
// function's taps, the elevational planes, log compression), without a label volume. Throws
// std::invalid_argument naming the ScanSpec field whose value needs more taps or planes than the
// kernels hold (bmode_bindings.h), or an image of no pixels.
kernels::BModeParams bmode_params(const ScanSpec& spec);
// ... and with the geometry of `labels` (uint8 tissue codes, checked below kTissueCount: throws
// std::invalid_argument naming the first voxel that is not).
kernels::BModeParams bmode_params(const ScanSpec& spec, const io::Volume& labels);
kernels::BModePose bmode_pose(const Pose& probe);

// The anatomy the frames at `poses` cover, as the kernels take it: tissue codes (uint8, Tissue) on
// a grid aligned with the frames (reconstruct.hpp's sweep box), `in_plane_mm` across the frames
// and `along_mm` between them, a voxel of margin all round. Voxelised on `threads` threads (0: all
// cores), sampling the medium on a grid twice as coarse first and only where the tissue differs in
// a block's neighbourhood (0.9 mm across) at every voxel: a feature thinner than the coarse step
// (0.4 mm at the defaults) with the same tissue either side can fall between the coarse samples.
struct LabelVolumeOptions {
    double in_plane_mm = 0.2;  // the tissue codes' step in the image plane: half a lateral PSF width
    double along_mm = 1.0;     // between frames: the anatomy changes slowly along the limb
    int threads = 0;
};
io::Volume voxelise_frames(const Medium& medium, std::span<const Pose> poses, const ScanSpec& spec, const LabelVolumeOptions& options = {});

// The image at `probe` with the tissue of each pixel looked up in `labels` (nearest voxel; outside
// it: gel): the GPU kernels' twin, to within rounding (tests/image/bmode_gpu_test.cpp).
BModeImage synthesize(const io::Volume& labels, const Pose& probe, const ScanSpec& spec);
// The same with the parameters made once (bmode_params(spec, labels)), for many frames.
BModeImage synthesize(const io::Volume& labels, const kernels::BModeParams& params, const Pose& probe);

// Live frames (generative imaging): the B-mode model run on each frame of the echographic image,
// its tissue looked up where it rests. The parameters for a live image `plane` (its rows and
// columns may be pixels of two sizes: the axial tables by the rows', the lateral PSF by the
// columns'); the rest of the scanner's settings from `spec` (its width, depth and pixel unused).
kernels::BModeParams bmode_live_params(const ImagePlane& plane, ScanSpec spec = {});
// The twin of a live frame's kernels (compute/bmode_live.comp, then the sweep's passes 2 to 4): the
// image of the probe pressed at `pressed` whose pixels show the tissue resting where the deform map
// `map` (deform_bindings.h: source y [mm], gain [dB] a pair, slice.map_columns x rows pairs; empty
// when nothing is pressed) puts it, `slice` the frame's slice parameters (echo::make_kernel_params:
// the plane, the map's geometry, the pressed probe to `labels`' voxels; SLICE_WARPED: the map is
// read). Throws std::invalid_argument for labels that are not uint8 or a map of the wrong size.
BModeImage synthesize_live(const io::Volume& labels, const kernels::BModeParams& params, const kernels::SliceParams& slice,
                           const Pose& pressed, std::span<const float> map);

// The phantom as a medium.
class PhantomMedium : public Medium {
public:
    explicit PhantomMedium(const Phantom& p) : phantom_(p) {}
    Tissue tissue_at(const glm::dvec3& world) const override { return phantom_.tissue_at(world); }

private:
    const Phantom& phantom_;
};

}  // namespace echosim::echo

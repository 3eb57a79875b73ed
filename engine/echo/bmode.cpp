#include "echo/bmode.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/matrix.hpp>

#include "core/fork_join.hpp"
#include "echo/log_compress.hpp"
#include "echo/reconstruct.hpp"
#include "echo/slice_cpu.hpp"
#include "echo/sweep.hpp"

namespace echosim::echo {
namespace {

// Acoustic properties by tissue: scattering strength (relative), impedance [MRayl], attenuation
// [dB/cm/MHz]. Blood barely scatters (anechoic lumen); an acute thrombus is hypo-echoic, a chronic
// one echogenic; bone reflects most of the energy and absorbs the rest.
struct Acoustics {
    float scatter;
    float impedance;
    float attenuation;
};
constexpr std::array<Acoustics, kTissueCount> kAcoustics = {{
    {0.0f, 1.50f, 0.002f},   // outside the skin: the coupling gel (anechoic)
    {1.3f, 1.62f, 1.0f},     // skin
    {0.45f, 1.38f, 0.6f},    // fat
    {1.1f, 1.68f, 0.9f},     // fascia
    {0.7f, 1.70f, 0.9f},     // muscle
    {0.02f, 1.61f, 0.15f},   // artery lumen (blood)
    {1.5f, 1.72f, 1.0f},     // artery wall
    {0.02f, 1.61f, 0.15f},   // vein lumen
    {1.2f, 1.76f, 1.0f},     // vein wall: collagen, denser than muscle (its intima echoes)
    {0.12f, 1.63f, 0.3f},    // acute thrombus: hypo-echoic
    {0.02f, 1.61f, 0.15f},   // saphenous lumen
    {2.0f, 7.80f, 20.0f},    // bone cortex
    {0.3f, 1.50f, 10.0f},    // marrow
    {0.9f, 1.68f, 0.6f},     // organised (chronic) thrombus: echogenic
    {1.8f, 1.74f, 1.2f},     // a chronic thrombus' scarred vein wall: thick, bright
    {0.1f, 1.62f, 0.5f},     // lymph node cortex: hypo-echoic
}};
// a specular echo relative to a unit scatterer: an interface of soft tissues (reflection 0.02 to
// 0.05: fat and muscle, blood and a vessel's wall) 10 to 18 dB over the speckle, as a fascia or a
// vessel's wall shows on a scanner (40, 20 dB over it at a perfect reflector, left them in the
// speckle: no fascial plane, and a vein pressed closed vanished where its walls meet as one line)
constexpr float kSpecular = 160.0f;
constexpr double kLattice = 0.1;    // scatterer lattice [mm]
// the live frames' elevational planes' spacing [mm]: one lattice step, as the sweeps'. The
// interpolated field (bmode_smooth_scatterer) is as good as independent over two steps, but planes
// that far apart made the speckle decorrelate within 0.05 mm of elevational motion (NCC 0.44) where
// the beam's thickness keeps it over about a millimetre: 17 planes at the probe's 1.2 mm slice
constexpr double kLiveElevationStepMm = 0.1;
static_assert(kTissueCount <= BMODE_MAX_TISSUES, "the kernels' tissue tables hold BMODE_MAX_TISSUES codes");
static_assert(BMODE_VEIN_LUMEN == unsigned(Tissue::vein_lumen) && BMODE_SAPHENOUS_LUMEN == unsigned(Tissue::saphenous_lumen),
              "bmode_coapted's closing lumens are echo::Tissue's");

std::vector<float> gaussian(double fwhm_mm, double pixel_mm)
{
    const double sigma = fwhm_mm / 2.3548 / pixel_mm;
    const int radius = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<float> k(std::size_t(2 * radius + 1));
    for (int i = -radius; i <= radius; ++i) k[std::size_t(i + radius)] = float(std::exp(-0.5 * i * i / (sigma * sigma)));
    return k;
}

// element i of a vec4-packed table
void put(glm::vec4* table, std::size_t i, float value) { table[i / 4][int(i % 4)] = value; }

using glm::vec2;
using glm::vec3;

// What pass 1 takes of a pixel: where its tissue rests (world mm) and which tissue it is.
struct PixelSource {
    vec3 world;
    std::uint32_t tissue;
};

// The twin of the four kernels for one frame, pass 1 (bmode_scatter.comp, or bmode_live.comp) from
// `source_of(c, r)`, a PixelSource.
template <class SourceOf>
BModeImage run_twin(const kernels::BModeParams& k, const kernels::BModePose& pose, SourceOf&& source_of, bool live = false)
{
    BModeImage img;
    img.width = k.columns;
    img.height = k.rows;
    const std::size_t w = k.columns, h = k.rows, n = w * h;
    img.labels.resize(n);
    std::vector<vec2> field(n), axial(n);

    // pass 1: scatter
    for (std::uint32_t r = 0; r < k.rows; ++r)
        for (std::uint32_t c = 0; c < k.columns; ++c) {
            const PixelSource source = source_of(c, r);
            const std::uint32_t t = source.tissue < k.tissue_count ? source.tissue : 0u;
            const std::size_t at = r * w + c;
            field[at] = kernels::bmode_scattered(source.world, vec3(pose.z), t, live, k);
            img.labels[at] = std::uint8_t(t);
        }
    // pass 2: down each beam (bmode_beam.comp), into `beam`
    std::vector<vec2> beam(n);
    for (std::size_t c = 0; c < w; ++c) {
        float transmitted = 1.0f;
        std::uint32_t above = 0;
        for (std::size_t r = 0; r < h; ++r) {
            const std::size_t at = r * w + c;
            const std::uint32_t t = img.labels[at];
            beam[at] = kernels::bmode_beam_step(field[at], above, t, r == 0, transmitted, k);
            above = t;
        }
    }
    // pass 3: the axial PSF (bmode_axial.comp)
    const int ra = int(k.axial_radius), rows = int(h);
    for (int r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < w; ++c) {
            vec2 s(0.0f);
            for (int d = -ra; d <= ra; ++d) {
                const int rr = r + d;
                if (rr >= 0 && rr < rows) s = s + beam[std::size_t(rr) * w + c] * kernels::bmode_axial_tap(std::uint32_t(d + ra), k);
            }
            axial[std::size_t(r) * w + c] = s;
        }
    // pass 4: the lateral PSF, the envelope, log compression (bmode_lateral.comp)
    img.envelope.resize(n);
    img.pixels.resize(n);
    const int rl = int(k.lateral_radius), columns = int(w);
    const LogCompressParams post{0, k.reference, k.gain_db, k.dynamic_range_db};
    for (std::size_t r = 0; r < h; ++r)
        for (int c = 0; c < columns; ++c) {
            vec2 s(0.0f);
            for (int d = -rl; d <= rl; ++d) {
                const int cc = c + d;
                if (cc >= 0 && cc < columns) s = s + axial[r * w + std::size_t(cc)] * kernels::bmode_lateral_tap(std::uint32_t(d + rl), k);
            }
            const std::size_t at = r * w + std::size_t(c);
            img.envelope[at] = kernels::bmode_envelope(s);
            img.pixels[at] = std::uint8_t(log_compress_pixel(img.envelope[at], post) & 0xffu);
        }
    return img;
}

}  // namespace

double attenuation_db_cm_mhz(Tissue t) { return kAcoustics[std::size_t(t)].attenuation; }

kernels::BModeParams bmode_params(const ScanSpec& spec)
{
    kernels::BModeParams k{};
    k.columns = spec.columns();
    k.rows = spec.rows();
    if (k.columns == 0 || k.rows == 0 || !(spec.pixel_mm > 0))
        throw std::invalid_argument("ScanSpec: an image of " + std::to_string(k.columns) + " x " + std::to_string(k.rows) + " pixels");
    k.row_words = (k.columns + 3) / 4;
    k.tissue_count = kTissueCount;
    k.texture = spec.texture ? 1u : 0u;
    k.pixel_mm = float(spec.pixel_mm);
    k.width_mm = float(spec.width_mm);
    k.lattice_inverse = float(1.0 / kLattice);
    k.specular = kSpecular;
    k.gain_db = float(spec.gain_db);
    k.dynamic_range_db = float(spec.dynamic_range_db);
    k.muscle_cells = glm::vec4(float(1 / 0.6), float(1 / 0.6), float(1 / 12.0), 0.0f);
    k.fat_cells = glm::vec4(float(1 / 1.5), float(1 / 0.4), float(1 / 6.0), 0.0f);

    // the tissues' tables: scattering; the round trip through one pixel less the compensation the
    // scanner applies; the reflection at each pair's interface and what passes on
    const double neper_per_db = std::log(10.0) / 20.0;
    for (std::size_t t = 0; t < kTissueCount; ++t) {
        put(k.scatter, t, kAcoustics[t].scatter);
        const double db = 2.0 * (kAcoustics[t].attenuation - spec.tgc_db_per_cm_mhz) * spec.frequency_mhz * spec.pixel_mm / 10.0;
        put(k.step, t, float(std::exp(-db * neper_per_db)));
        for (std::size_t u = 0; u < kTissueCount; ++u) {
            const double z1 = kAcoustics[t].impedance, z2 = kAcoustics[u].impedance;
            const double r = std::abs(z2 - z1) / (z2 + z1);
            put(k.reflect, t * BMODE_MAX_TISSUES + u, float(r));
            put(k.pass, t * BMODE_MAX_TISSUES + u, float(1.0 - r * r));
        }
    }

    // elevational planes one lattice step apart, weighted by the beam's profile: a probe moved a
    // fraction of a step still sums nearly the same scatterers, so its speckle changes smoothly
    const double sigma_e = spec.elevational_fwhm_mm / 2.3548;
    const int reach = int(std::ceil(1.5 * sigma_e / kLattice));
    if (2 * reach + 1 > BMODE_MAX_PLANES)
        throw std::invalid_argument("ScanSpec.elevational_fwhm_mm: " + std::to_string(spec.elevational_fwhm_mm) + " mm needs " +
                                    std::to_string(2 * reach + 1) + " planes, the kernels hold " + std::to_string(BMODE_MAX_PLANES));
    for (int e = -reach; e <= reach; ++e) {
        const double z = e * kLattice;
        k.elevation[k.planes++] = glm::vec4(float(z), float(std::exp(-0.5 * z * z / (sigma_e * sigma_e))), 0.0f, 0.0f);
    }

    // the point-spread function, separable
    const std::vector<float> ka = gaussian(spec.axial_fwhm_mm, spec.pixel_mm), kl = gaussian(spec.lateral_fwhm_mm, spec.pixel_mm);
    for (const auto& [taps, field] : {std::pair{&ka, "axial_fwhm_mm"}, std::pair{&kl, "lateral_fwhm_mm"}})
        if (taps->size() > BMODE_MAX_TAPS)
            throw std::invalid_argument(std::string("ScanSpec.") + field + ": " + std::to_string(taps->size()) + " taps at " +
                                        std::to_string(spec.pixel_mm) + " mm pixels, the kernels hold " + std::to_string(BMODE_MAX_TAPS));
    k.axial_radius = std::uint32_t(ka.size() / 2);
    k.lateral_radius = std::uint32_t(kl.size() / 2);
    for (std::size_t i = 0; i < ka.size(); ++i) put(k.axial, i, ka[i]);
    for (std::size_t i = 0; i < kl.size(); ++i) put(k.lateral, i, kl[i]);

    // log compression: a unit-strength scatterer field shows about 20 dB under white
    float psf_gain = 0;
    for (float a : ka)
        for (float l : kl) psf_gain += a * a * l * l;
    k.reference = 10.0f * std::sqrt(psf_gain * float(k.planes));
    return k;
}

kernels::BModeParams bmode_params(const ScanSpec& spec, const io::Volume& labels)
{
    kernels::BModeParams k = bmode_params(spec);
    if (labels.type != io::VoxelType::uint8) throw std::invalid_argument("the label volume's voxels are not uint8 tissue codes");
    const std::uint8_t* codes = labels.as<std::uint8_t>();
    for (std::size_t i = 0; i < labels.voxel_count(); ++i)
        if (codes[i] >= kTissueCount)
            throw std::invalid_argument("the label volume's voxel " + std::to_string(i) + " holds " + std::to_string(codes[i]) +
                                        ", not a tissue code (0.." + std::to_string(kTissueCount - 1) + ")");
    k.volume_size_x = std::uint32_t(labels.size[0]);
    k.volume_size_y = std::uint32_t(labels.size[1]);
    k.volume_size_z = std::uint32_t(labels.size[2]);
    k.volume_origin = glm::vec4(glm::vec3(labels.origin), 1.0f);
    const glm::dmat3 inverse = glm::inverse(labels.directions);
    for (int a = 0; a < 3; ++a) k.volume_inverse[a] = glm::vec4(glm::vec3(glm::row(inverse, a)), 0.0f);
    return k;
}

kernels::BModePose bmode_pose(const Pose& probe)
{
    return {glm::vec4(probe.position, 1.0f), glm::vec4(probe.axis_x(), 0.0f), glm::vec4(probe.axis_y(), 0.0f),
            glm::vec4(probe.axis_z(), 0.0f)};
}

BModeImage synthesize(const Medium& medium, const Pose& pose, const ScanSpec& spec)
{
    const kernels::BModeParams k = bmode_params(spec);
    const kernels::BModePose f = bmode_pose(pose);
    return run_twin(k, f, [&](std::uint32_t c, std::uint32_t r) {
        const vec3 p = kernels::bmode_pixel_world(f, c, r, k.pixel_mm, k.width_mm);
        return PixelSource{p, std::uint32_t(medium.tissue_at(glm::dvec3(p)))};
    });
}

BModeImage synthesize(const io::Volume& labels, const kernels::BModeParams& params, const Pose& pose)
{
    const std::uint8_t* codes = labels.as<std::uint8_t>();
    const kernels::BModePose f = bmode_pose(pose);
    return run_twin(params, f, [&](std::uint32_t c, std::uint32_t r) {
        const vec3 p = kernels::bmode_pixel_world(f, c, r, params.pixel_mm, params.width_mm);
        const int voxel = kernels::bmode_voxel(p, params);
        return PixelSource{p, voxel < 0 ? 0u : std::uint32_t(codes[voxel])};
    });
}

kernels::BModeParams bmode_live_params(const ImagePlane& plane, ScanSpec spec)
{
    // the tables and the axial PSF go down the beam, a row a pixel; the lateral PSF across it
    spec.width_mm = plane.width_mm;
    spec.depth_mm = plane.depth_mm;
    spec.pixel_mm = plane.pixel_y_mm();
    kernels::BModeParams k = bmode_params(spec);
    ScanSpec across = spec;
    across.pixel_mm = plane.pixel_x_mm();
    const kernels::BModeParams lateral = bmode_params(across);
    k.lateral_radius = lateral.lateral_radius;
    std::copy(std::begin(lateral.lateral), std::end(lateral.lateral), std::begin(k.lateral));
    k.columns = plane.columns;
    k.rows = plane.rows;
    k.row_words = (k.columns + 3) / 4;
    k.pixel_mm = float(plane.pixel_y_mm());
    // the elevational planes of the interpolated field (bmode_elevation_sum), kLiveElevationStepMm apart
    const double sigma_e = spec.elevational_fwhm_mm / 2.3548;
    const int reach = int(std::ceil(1.5 * sigma_e / kLiveElevationStepMm));
    if (2 * reach + 1 > BMODE_MAX_PLANES)
        throw std::invalid_argument("ScanSpec.elevational_fwhm_mm: " + std::to_string(spec.elevational_fwhm_mm) + " mm needs " +
                                    std::to_string(2 * reach + 1) + " planes, the kernels hold " + std::to_string(BMODE_MAX_PLANES));
    k.planes = 0;
    for (int e = -reach; e <= reach; ++e) {
        const double z = e * kLiveElevationStepMm;
        k.elevation[k.planes++] = glm::vec4(float(z), float(std::exp(-0.5 * z * z / (sigma_e * sigma_e))), 0.0f, 0.0f);
    }
    // log compression as the sweeps' (bmode_params): a unit scatterer field about 20 dB under white
    float psf_gain = 0;
    for (std::uint32_t a = 0; a <= 2 * k.axial_radius; ++a)
        for (std::uint32_t l = 0; l <= 2 * k.lateral_radius; ++l) {
            const float ta = kernels::bmode_axial_tap(a, k), tl = kernels::bmode_lateral_tap(l, k);
            psf_gain += ta * ta * tl * tl;
        }
    k.reference = 10.0f * std::sqrt(psf_gain * float(k.planes));
    return k;
}

BModeImage synthesize_live(const io::Volume& labels, const kernels::BModeParams& params, const kernels::SliceParams& slice,
                           const Pose& pressed, std::span<const float> map)
{
    if (labels.type != io::VoxelType::uint8) throw std::invalid_argument("the label volume's voxels are not uint8 tissue codes");
    if ((slice.flags & SLICE_WARPED) != 0u && map.size() != std::size_t(slice.map_columns) * slice.rows * 2)
        throw std::invalid_argument("synthesize_live: a deform map of " + std::to_string(map.size() / 2) + " entries, the plane needs " +
                                    std::to_string(std::size_t(slice.map_columns) * slice.rows));
    const kernels::BModePose f = bmode_pose(pressed);
    return run_twin(params, f, [&](std::uint32_t c, std::uint32_t r) {
        const SliceSample s = slice_sample(slice, map, c, r);
        const float above_y = r > 0 ? slice_sample(slice, map, c, r - 1).map.x : s.map.x;
        std::uint32_t t = label_at(labels, s.index);
        // (as the kernel: the tissue halfway across a skip looked up only where the map skips)
        if (s.map.x - above_y > BMODE_COAPTED_SKIP_MM) {
            const glm::vec3 middle = glm::vec3(slice.probe_to_index * glm::vec4(s.x, 0.5f * (s.map.x + above_y), 0.0f, 1.0f));
            t = kernels::bmode_coapted(t, label_at(labels, middle), s.map.x - above_y);
        }
        return PixelSource{kernels::bmode_live_world(f, s.x, s.map.x), t};
    }, true);
}

BModeImage synthesize(const io::Volume& labels, const Pose& pose, const ScanSpec& spec)
{
    return synthesize(labels, bmode_params(spec, labels), pose);
}

io::Volume voxelise_frames(const Medium& medium, std::span<const Pose> poses, const ScanSpec& spec, const LabelVolumeOptions& options)
{
    if (poses.empty()) throw std::invalid_argument("voxelise_frames: no frames");
    if (!(options.in_plane_mm > 0) || !(options.along_mm > 0))
        throw std::invalid_argument("LabelVolumeOptions: in_plane_mm and along_mm must be positive");
    std::vector<glm::dmat4> frames;
    for (const Pose& p : poses) frames.push_back(image_to_world(p, spec));
    const SweepBox box = sweep_box(frames, spec.columns(), spec.rows());
    const glm::dvec3 spacing(options.in_plane_mm, options.in_plane_mm, options.along_mm);
    // a voxel of margin beyond the pixel centres' box, so the nearest voxel of every pixel is inside
    const glm::dvec3 lo = box.lo - spacing, hi = box.hi + spacing;
    std::array<std::size_t, 3> size{};
    for (int a = 0; a < 3; ++a) size[std::size_t(a)] = std::size_t(std::ceil((hi[a] - lo[a]) / spacing[a])) + 1;
    io::Volume v = io::make_volume(size, io::VoxelType::uint8);
    v.origin = box.axes * lo;
    v.directions = glm::dmat3(box.axes[0] * spacing.x, box.axes[1] * spacing.y, box.axes[2] * spacing.z);
    for (int t = 0; t < kTissueCount; ++t) v.key_values["label_" + std::to_string(t)] = tissue_name(Tissue(t));

    // per slice: the medium on a grid of twice the step, then, in each 2 x 2 block, the block's
    // tissue where its 4 x 4 coarse neighbourhood agrees, else the medium at each voxel
    constexpr std::size_t B = 2;
    const std::size_t nx = size[0], ny = size[1], cx = (nx + B - 1) / B + 1, cy = (ny + B - 1) / B + 1;
    std::uint8_t* out = v.as<std::uint8_t>();
    const auto world = [&](double i, double j, double k) { return v.index_to_world(glm::dvec3(i, j, k)); };
    const int threads = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    ForkJoin team(std::min(threads, ForkJoin::kMaxParts));
    team.run([&](int part) {
        std::vector<std::uint8_t> coarse(cx * cy);
        for (std::size_t k = std::size_t(part); k < size[2]; k += std::size_t(team.parts())) {
            for (std::size_t b = 0; b < cy; ++b)
                for (std::size_t a = 0; a < cx; ++a) coarse[b * cx + a] = std::uint8_t(medium.tissue_at(world(double(a * B), double(b * B), double(k))));
            std::uint8_t* slice = out + k * nx * ny;
            for (std::size_t b = 0; b + 1 < cy; ++b)
                for (std::size_t a = 0; a + 1 < cx; ++a) {
                    const std::uint8_t t = coarse[b * cx + a];
                    bool uniform = true;
                    for (std::size_t bb = b > 0 ? b - 1 : 0; bb <= std::min(b + 2, cy - 1) && uniform; ++bb)
                        for (std::size_t aa = a > 0 ? a - 1 : 0; aa <= std::min(a + 2, cx - 1) && uniform; ++aa) uniform = coarse[bb * cx + aa] == t;
                    for (std::size_t j = b * B; j < std::min(b * B + B, ny); ++j)
                        for (std::size_t i = a * B; i < std::min(a * B + B, nx); ++i)
                            slice[j * nx + i] = uniform || (i == a * B && j == b * B)
                                                    ? (uniform ? t : coarse[b * cx + a])
                                                    : std::uint8_t(medium.tissue_at(world(double(i), double(j), double(k))));
                }
        }
    });
    return v;
}

}  // namespace echosim::echo

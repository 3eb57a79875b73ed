#include "echo/case_volume.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "echo/reconstruct.hpp"

namespace echosim::echo {
namespace {

// The box of the frames' corners in the axes that hold them with the least volume: turned about the
// limb's axis (world z) and tilted about the turned x, a coarse search (the course bends from the
// anterior-medial thigh to the back of the knee, so no one frame's axes suit it).
SweepBox smallest_box(const std::vector<glm::dmat4>& frames, std::uint32_t width, std::uint32_t height)
{
    std::vector<glm::dvec3> corners;
    for (const glm::dmat4& m : frames)
        for (double c : {0.0, double(width - 1)})
            for (double r : {0.0, double(height - 1)}) corners.push_back(glm::dvec3(m * glm::dvec4(c, r, 0, 1)));
    SweepBox best;
    double least = std::numeric_limits<double>::infinity();
    for (double turn = 0; turn < 180; turn += 3)
        for (double tilt = -30; tilt <= 30; tilt += 2) {
            const glm::dmat3 axes(glm::rotate(glm::dmat4(1.0), glm::radians(turn), glm::dvec3(0, 0, 1)) *
                                  glm::rotate(glm::dmat4(1.0), glm::radians(tilt), glm::dvec3(1, 0, 0)));
            const glm::dmat3 to_box = glm::transpose(axes);
            glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
            for (const glm::dvec3& c : corners) {
                const glm::dvec3 q = to_box * c;
                lo = glm::min(lo, q);
                hi = glm::max(hi, q);
            }
            const glm::dvec3 size = hi - lo;
            if (size.x * size.y * size.z < least) {
                least = size.x * size.y * size.z;
                best = {axes, lo, hi};
            }
        }
    return best;
}

std::string describe(const Anatomy& a)
{
    char text[160];
    std::snprintf(text, sizeof text, "fat %g mm", a.fat_mm);
    std::string out = text;
    for (const Thrombus& t : a.thrombi) {
        std::snprintf(text, sizeof text, "; %s %s thrombus %g..%g cm, %g occlusive", thrombus_kind_name(t.kind), segment_name(t.segment),
                      t.start_cm, t.start_cm + t.extent_cm, t.occlusion);
        out += text;
    }
    for (const LymphNode& n : a.lymph_nodes) {
        std::snprintf(text, sizeof text, "; lymph node %g mm at %g cm", n.size_mm, n.s_cm);
        out += text;
    }
    return out;
}

}  // namespace

CaseVolumeOptions coarse_case_volume_options()
{
    CaseVolumeOptions o;
    o.voxel_mm = 0.6;
    o.pixel_mm = 0.3;
    o.frames /= 4;
    return o;
}

std::vector<Pose> course_sweep_poses(const Phantom& phantom, int frames)
{
    if (frames < 2) throw std::invalid_argument("a case volume's sweep needs at least 2 frames");
    struct Pass {
        VeinSegment segment;
        double from_cm, to_cm;
    };
    const Pass passes[] = {{VeinSegment::fv, kDeepVeinFrom_cm + 0.5, kAdductorHiatus_cm + 1.0},
                           {VeinSegment::popliteal, kAdductorHiatus_cm - 1.0, kTrifurcation_cm}};
    double length = 0;
    for (const Pass& p : passes) length += p.to_cm - p.from_cm;
    std::vector<Pose> poses;
    int left = frames;
    for (std::size_t k = 0; k < std::size(passes); ++k) {
        const Pass& p = passes[k];
        const int n = k + 1 == std::size(passes) ? left : std::max(2, int(std::lround(frames * (p.to_cm - p.from_cm) / length)));
        left -= n;
        for (int f = 0; f < n; ++f) poses.push_back(phantom.transverse_probe_pose(p.segment, p.from_cm + (p.to_cm - p.from_cm) * f / std::max(1, n - 1)));
    }
    return poses;
}

CaseVolume make_case_volume(const scene::LegModel& leg, const Anatomy& anatomy, const CaseVolumeOptions& options,
                            const std::function<void(const std::string&, double)>& progress)
{
    const auto tell = [&](const std::string& stage, double done) {
        if (progress) progress(stage, done);
    };
    if (options.chunk_frames < 1) throw std::invalid_argument("CaseVolumeOptions::chunk_frames must be at least 1");
    const Phantom phantom(leg, anatomy);
    const PhantomMedium medium(phantom);
    ScanSpec spec;
    spec.pixel_mm = options.pixel_mm;
    spec.depth_mm = options.depth_mm;
    spec.width_mm = options.width_mm;
    const std::vector<Pose> poses = course_sweep_poses(phantom, options.frames);
    std::vector<glm::dmat4> frames;
    for (const Pose& p : poses) frames.push_back(image_to_world(p, spec));
    const std::uint32_t width = spec.columns(), height = spec.rows();

    const SweepBox box = smallest_box(frames, width, height);
    ReconstructOptions reconstruct;
    reconstruct.voxel_mm = options.voxel_mm;
    const glm::dvec3 margin(options.voxel_mm);
    Reconstructor r(box.lo - margin, box.hi + margin, reconstruct, box.axes);

    // chunk by chunk: the chunk's anatomy voxelised, its frames imaged, pasted into the map
    const std::string stage = "imaging the course (" + std::to_string(poses.size()) + " frames)";
    const std::size_t frame_bytes = std::size_t(width) * height;
    std::vector<std::uint8_t> pixels, labels;
    for (std::size_t first = 0; first < poses.size(); first += std::size_t(options.chunk_frames)) {
        tell(stage, double(first) / double(poses.size()));
        const std::span<const Pose> chunk = std::span(poses).subspan(first, std::min(std::size_t(options.chunk_frames), poses.size() - first));
        const auto anatomy_labels = std::make_shared<const io::Volume>(voxelise_frames(medium, chunk, spec, options.anatomy));
        const std::unique_ptr<SweepImager> imager =
            options.imager ? options.imager(anatomy_labels, spec) : std::make_unique<CpuSweepImager>(anatomy_labels, spec);
        pixels.resize(frame_bytes * chunk.size());
        labels.resize(frame_bytes * chunk.size());
        const std::size_t batch = std::max<std::size_t>(1, imager->batch_frames());
        for (std::size_t f = 0; f < chunk.size(); f += batch)
            imager->image(chunk.subspan(f, std::min(batch, chunk.size() - f)), pixels.data() + f * frame_bytes, labels.data() + f * frame_bytes);
        for (std::size_t f = 0; f < chunk.size(); ++f)
            r.insert(std::span(pixels.data() + f * frame_bytes, frame_bytes), std::span(labels.data() + f * frame_bytes, frame_bytes), width,
                     height, frames[first + f]);
    }
    tell(stage, 1.0);
    r.fill_holes([&](double done) { tell("filling holes", done); });
    CaseVolume out{r.volume(), r.labels()};
    for (io::Volume* v : {&out.volume, &out.labels}) v->key_values["anatomy"] = describe(anatomy);
    for (int t = 0; t < kTissueCount; ++t) out.labels.key_values["label_" + std::to_string(t)] = tissue_name(Tissue(t));
    return out;
}

CaseVolume make_case_volume(const scene::LegModel& leg, Case which, const CaseVolumeOptions& options,
                            const std::function<void(const std::string&, double)>& progress)
{
    CaseVolume out = make_case_volume(leg, anatomy_of(which), options, progress);
    out.volume.key_values["case"] = case_name(which);
    out.labels.key_values["case"] = case_name(which);
    return out;
}

}  // namespace echosim::echo

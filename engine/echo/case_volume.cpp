#include "echo/case_volume.hpp"

#include "echo/reconstruct.hpp"
#include "echo/sweep.hpp"

namespace echosim::echo {

CaseVolume make_case_volume(const scene::LegModel& leg, Case which, const CaseVolumeOptions& options,
                            const std::function<void(const std::string&, double)>& progress)
{
    const auto tell = [&](const char* stage, double done) {
        if (progress) progress(stage, done);
    };
    const Phantom phantom(leg, which);
    const PhantomMedium medium(phantom);
    SweepOptions sweep_options;
    sweep_options.frames = options.frames;
    sweep_options.spec.pixel_mm = options.pixel_mm;
    sweep_options.spec.depth_mm = options.depth_mm;
    tell("voxelising the anatomy", 0.0);
    const auto labels = std::make_shared<const io::Volume>(voxelise_frames(medium, sweep_poses(leg, sweep_options), sweep_options.spec, options.anatomy));
    const std::unique_ptr<SweepImager> imager =
        options.imager ? options.imager(labels, sweep_options.spec) : std::make_unique<CpuSweepImager>(labels, sweep_options.spec);
    const TrackedSweep sweep = make_sweep(leg, *imager, sweep_options, [&](int done, int total) { tell("imaging the sweep", double(done) / total); });

    const SweepBox box = sweep_box(sweep.sweep);
    ReconstructOptions reconstruct;
    reconstruct.voxel_mm = options.voxel_mm;
    const glm::dvec3 margin(options.voxel_mm);
    Reconstructor r(box.lo - margin, box.hi + margin, reconstruct, box.axes);
    const std::size_t frame_bytes = sweep.sweep.frame_bytes();
    for (std::size_t f = 0; f < sweep.sweep.frames.size(); ++f) {
        r.insert(std::span(sweep.sweep.frame_pixels(f), frame_bytes), std::span(sweep.labels.data() + f * frame_bytes, frame_bytes),
                 sweep.sweep.width, sweep.sweep.height, sweep.sweep.frames[f].image_to_reference);
        tell("reconstructing", double(f + 1) / double(sweep.sweep.frames.size()));
    }
    r.fill_holes([&](double done) { tell("filling holes", done); });
    CaseVolume out{r.volume(), r.labels()};
    out.volume.key_values["case"] = case_name(which);
    out.labels.key_values["case"] = case_name(which);
    for (int t = 0; t < kTissueCount; ++t) out.labels.key_values["label_" + std::to_string(t)] = tissue_name(Tissue(t));
    return out;
}

}  // namespace echosim::echo

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>


#include <glm/vec3.hpp>

#include "app/commands.hpp"
#include "echo/phantom.hpp"
#include "echo/reconstruct.hpp"
#include "io/nrrd.hpp"
#include "io/plus_sequence.hpp"

namespace echosim::app {

std::filesystem::path label_sweep_path(const std::filesystem::path& sweep);  // cmd_phantom.cpp

int run_reconstruct(const ReconstructArgs& args)
{
    using clock = std::chrono::steady_clock;
    if (!output_folder_exists("reconstruct", "--out", args.out)) return kExitBadInput;
    io::Sweep sweep, labels;
    try {
        sweep = io::read_plus_sequence(args.sweep);
        if (std::filesystem::exists(label_sweep_path(args.sweep))) labels = io::read_plus_sequence(label_sweep_path(args.sweep));
    } catch (const io::PlusSequenceError& e) {
        std::fprintf(stderr, "echosim reconstruct: %s\n", e.what());
        return kExitBadInput;
    }
    const bool with_labels = labels.frames.size() == sweep.frames.size() && labels.width == sweep.width && labels.height == sweep.height;

    const auto valid = std::size_t(std::count_if(sweep.frames.begin(), sweep.frames.end(), [](const auto& f) { return f.valid; }));
    if (valid == 0) {
        std::fprintf(stderr, "echosim reconstruct: %s: no frame has a valid transform\n", args.sweep.c_str());
        return kExitBadInput;
    }
    const echo::SweepBox box = echo::sweep_box(sweep);
    echo::ReconstructOptions options;
    options.voxel_mm = args.voxel_mm;
    options.splat = args.splat == "nearest" ? echo::Splat::nearest : echo::Splat::trilinear;
    options.compounding = args.compound == "max" ? echo::Compounding::max : echo::Compounding::mean;
    options.memory_budget_bytes = std::uint64_t(args.budget_mb) << 20;
    const glm::dvec3 margin(options.voxel_mm);
    std::unique_ptr<echo::Reconstructor> r;
    try {
        r = std::make_unique<echo::Reconstructor>(box.lo - margin, box.hi + margin, options, box.axes);
    } catch (const std::runtime_error& e) {
        std::fprintf(stderr, "echosim reconstruct: %s\n", e.what());
        return kExitBadInput;
    }

    const auto t0 = clock::now();
    for (std::size_t f = 0; f < sweep.frames.size(); ++f) {
        if (!sweep.frames[f].valid) continue;
        const std::span<const std::uint8_t> px(sweep.frame_pixels(f), sweep.frame_bytes());
        const std::span<const std::uint8_t> lb = with_labels ? std::span<const std::uint8_t>(labels.frame_pixels(f), labels.frame_bytes())
                                                             : std::span<const std::uint8_t>();
        r->insert(px, lb, sweep.width, sweep.height, sweep.frames[f].image_to_reference);
        if ((f + 1) % 20 == 0 || f + 1 == sweep.frames.size())
            std::fprintf(stderr, "\rechosim reconstruct: inserted %zu of %zu frames", f + 1, sweep.frames.size());
    }
    const double insert_s = std::chrono::duration<double>(clock::now() - t0).count();
    std::fprintf(stderr, "\n");
    const double covered = double(r->filled_voxels()) / double(r->voxel_count());
    const auto t1 = clock::now();
    const int passes = r->fill_holes([](double done) { std::fprintf(stderr, "\rechosim reconstruct: holes filled %3.0f %%", 100 * done); });
    const double fill_s = std::chrono::duration<double>(clock::now() - t1).count();
    std::fprintf(stderr, "\n");

    io::Volume volume = r->volume();
    volume.key_values["echosim_source"] = args.sweep.filename().string();
    io::write_nrrd(args.out, volume, args.gzip);
    std::printf("echosim reconstruct: %zux%zux%zu voxels of %.2f mm (%llu MiB while working) in %s\n", volume.size[0], volume.size[1],
                volume.size[2], options.voxel_mm, static_cast<unsigned long long>(r->memory_bytes() >> 20), args.out.c_str());
    std::printf("echosim reconstruct: %zu frames in %.2f s (%.0f frames/s), %.1f %% of voxels hit, %.1f %% after filling holes "
                "(%d passes, %.2f s)\n",
                valid, insert_s, double(valid) / insert_s, 100 * covered, 100.0 * double(r->filled_voxels()) / double(r->voxel_count()),
                passes, fill_s);
    if (with_labels) {
        io::Volume l = r->labels();
        for (int t = 0; t < echo::kTissueCount; ++t) l.key_values["label_" + std::to_string(t)] = echo::tissue_name(echo::Tissue(t));
        std::filesystem::path lp = args.out;
        lp.replace_filename(args.out.stem().string() + ".labels.nrrd");
        io::write_nrrd(lp, l, true);
        std::printf("echosim reconstruct: labels in %s\n", lp.c_str());
    }
    return kExitOk;
}

}  // namespace echosim::app

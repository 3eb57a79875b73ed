#include <cstdio>
#include <string>

#include <glm/vec3.hpp>

#include "app/bmode_imager.hpp"
#include "app/commands.hpp"
#include "app/gpu_args.hpp"
#include "app/terminal_progress.hpp"
#include "echo/phantom.hpp"
#include "echo/reconstruct.hpp"
#include "echo/sweep.hpp"
#include "io/nrrd.hpp"
#include "io/plus_sequence.hpp"

namespace echosim::app {

std::filesystem::path label_sweep_path(const std::filesystem::path& sweep)
{
    std::string name = sweep.filename().string();
    const auto dot = name.find('.');
    name = (dot == std::string::npos ? name : name.substr(0, dot)) + ".labels.mha";
    return sweep.parent_path() / name;
}

int run_phantom(const PhantomArgs& args)
{
    echo::Case which;
    try {
        which = echo::parse_case(args.case_name);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "echosim phantom: --case: %s\n", e.what());
        return kExitBadInput;
    }
    const auto label_path = label_sweep_path(args.out);
    if (!output_path_usable("phantom", "--out", args.out) || !output_path_usable("phantom", "--out's label sweep", label_path) ||
        (!args.labels.empty() && !output_path_usable("phantom", "--labels", args.labels)) ||
        !outputs_distinct("phantom", {{"--out", args.out}, {"--out's label sweep", label_path}, {"--labels", args.labels}}, {}))
        return kExitBadInput;
    const scene::LegModel leg;
    const echo::Phantom phantom(leg, which);
    const echo::PhantomMedium medium(phantom);
    echo::SweepOptions options;
    options.frames = args.frames;
    options.seed = args.seed;
    options.spec.pixel_mm = args.pixel_mm;
    // the anatomy over the frames as a label volume, imaged on the GPU (else, or with --cpu, by
    // the CPU twin of its kernels: the same images to within a grey level)
    TerminalProgress progress("echosim phantom: ");
    progress("voxelising the anatomy", 0.0);
    const auto anatomy = std::make_shared<const io::Volume>(echo::voxelise_frames(medium, echo::sweep_poses(leg, options), options.spec));
    std::unique_ptr<echo::SweepImager> imager;
    try {
        if (args.cpu) imager = std::make_unique<echo::CpuSweepImager>(anatomy, options.spec);
        else imager = make_bmode_imager(anatomy, options.spec, context_options(args.gpu), "echosim phantom");
    } catch (const std::invalid_argument& e) {
        progress.finish();
        std::fprintf(stderr, "echosim phantom: %s\n", e.what());
        return kExitBadInput;
    }
    const echo::TrackedSweep sweep = echo::make_sweep(leg, *imager, options, [&](int done, int total) {
        progress("imaging the sweep (" + std::to_string(total) + " frames, " + imager->backend() + ")", double(done) / total);
    });
    progress.finish();
    // the frames' tissue labels, a sweep of their own beside it, for reconstructing the labels
    io::Sweep labels = sweep.sweep;
    labels.pixels = sweep.labels;

    io::Volume map;
    if (!args.labels.empty()) {
        // the phantom's own label map over the box the sweep spans, aligned with it as the
        // reconstruction's map is
        const echo::SweepBox box = echo::sweep_box(sweep.sweep);
        const double voxel = 0.3;
        map = io::make_volume({std::size_t((box.hi.x - box.lo.x) / voxel) + 1, std::size_t((box.hi.y - box.lo.y) / voxel) + 1,
                               std::size_t((box.hi.z - box.lo.z) / voxel) + 1},
                              io::VoxelType::uint8);
        map.origin = box.axes * box.lo;
        map.directions = box.axes * voxel;
        std::uint8_t* d = map.as<std::uint8_t>();
        for (std::size_t k = 0; k < map.size[2]; ++k)
            for (std::size_t j = 0; j < map.size[1]; ++j)
                for (std::size_t i = 0; i < map.size[0]; ++i)
                    d[map.index(i, j, k)] = std::uint8_t(phantom.tissue_at(map.index_to_world(glm::dvec3(double(i), double(j), double(k)))));
        for (int t = 0; t < echo::kTissueCount; ++t) map.key_values["label_" + std::to_string(t)] = echo::tissue_name(echo::Tissue(t));
        map.key_values["case"] = echo::case_name(which);
    }
    // the sweep, its labels and the map stay a set: all written, or none replaced
    std::vector<std::filesystem::path> outputs{args.out, label_path};
    if (!args.labels.empty()) outputs.push_back(args.labels);
    write_together(outputs, [&](std::size_t i, const std::filesystem::path& path) {
        if (i == 0) io::write_plus_mha(path, sweep.sweep, args.compressed);
        else if (i == 1) io::write_plus_mha(path, labels, true);
        else io::write_nrrd(path, map, true);
    });
    std::printf("echosim phantom: %s case, %zu frames of %ux%u (%.2f mm pixels, synthesised on %s) in %s, their labels in %s\n",
                echo::case_name(which), sweep.sweep.frames.size(), sweep.sweep.width, sweep.sweep.height, args.pixel_mm,
                imager->backend().c_str(), args.out.c_str(), label_path.c_str());
    if (!args.labels.empty())
        std::printf("echosim phantom: label map %zux%zux%zu (0.3 mm) in %s\n", map.size[0], map.size[1], map.size[2], args.labels.c_str());
    return kExitOk;
}

}  // namespace echosim::app

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <unistd.h>

#include "app/commands.hpp"
#include "app/terminal_progress.hpp"
#include "core/printable_text.hpp"
#include "echo/phantom.hpp"
#include "echo/reconstruct.hpp"
#include "io/nrrd.hpp"
#include "io/plus_config.hpp"
#include "io/plus_sequence.hpp"
#include "io/text_fields.hpp"
#include "io/transform_repository.hpp"
#include "io/volume_file.hpp"

namespace echosim::app {

std::filesystem::path label_sweep_path(const std::filesystem::path& sweep);  // cmd_phantom.cpp

namespace {

// What reconstruction is asked for: echosim's defaults, then the PLUS configuration's, then the
// command line's, each over the one before.
struct Plan {
    io::TransformRepository calibration;
    std::string image_frame = "Image";
    std::string reference_frame;  // empty: Reference, or Tracker when the recording names only that
    echo::ReconstructOptions options;
    glm::dvec3 spacing{0.3};
    bool fill_holes = true;
    bool plus_grid = false;
    std::optional<std::array<int, 6>> extent;  // with origin: the grid the configuration fixes
    glm::dvec3 origin{0.0};
    std::string clip_at;                        // "FILE:LINE: VolumeReconstruction", where the clip rectangle is given
    std::string extent_at;                      // the same for OutputOrigin and OutputExtent
    std::vector<io::PlusConfigTransform> config_transforms;
    std::vector<std::string> warnings;
};

Plan make_plan(const ReconstructArgs& args)
{
    Plan plan;
    if (!args.config.empty()) {
        const io::PlusConfig config = io::read_plus_config(args.config);
        plan.warnings = config.warnings;
        plan.config_transforms = config.transforms;
        for (const io::PlusConfigTransform& t : config.transforms) {
            try {
                plan.calibration.set(t.from, t.to, t.matrix, t.valid);
            } catch (const io::TransformError& e) {
                throw io::PlusConfigError(args.config.string() + ":" + std::to_string(t.line) + ": Transform: " + e.what());
            }
        }
        // PLUS's VolumeReconstructor defaults: nearest neighbour, mean, no hole filling, its grid
        plan.options.splat = echo::Splat::nearest;
        plan.fill_holes = false;
        plan.plus_grid = true;
        if (const auto& r = config.reconstruction) {
            const std::string at = args.config.string() + ":" + std::to_string(r->line) + ": VolumeReconstruction";
            plan.clip_at = plan.extent_at = at;
            if (r->output_spacing) plan.spacing = *r->output_spacing;
            if (r->output_origin) plan.origin = *r->output_origin, plan.extent = r->output_extent;
            if (r->clip_size && (*r->clip_size)[0] > 0 && (*r->clip_size)[1] > 0) {
                const auto& o = *r->clip_origin;
                const auto& s = *r->clip_size;
                plan.options.clip = {std::uint32_t(o[0]), std::uint32_t(o[1]), std::uint32_t(o[0] + s[0]), std::uint32_t(o[1] + s[1])};
            }
            if (r->interpolation)
                plan.options.splat = *r->interpolation == io::PlusInterpolation::linear ? echo::Splat::trilinear : echo::Splat::nearest;
            if (r->compounding)
                plan.options.compounding = *r->compounding == io::PlusCompounding::maximum ? echo::Compounding::max
                                           : *r->compounding == io::PlusCompounding::latest ? echo::Compounding::latest
                                                                                            : echo::Compounding::mean;
            if (r->fill_holes) plan.fill_holes = *r->fill_holes;
            if (r->pixel_rejection_threshold) plan.options.pixel_threshold = *r->pixel_rejection_threshold;
            plan.image_frame = r->image_frame;
            plan.reference_frame = r->reference_frame;
        }
    }
    if (!args.image_to_reference.empty()) {
        if (const auto names = io::split_transform_name(args.image_to_reference)) {
            plan.image_frame = names->first;
            plan.reference_frame = names->second;
        } else {
            plan.reference_frame = args.image_to_reference;
        }
    }
    if (args.voxel_mm) plan.spacing = glm::dvec3(*args.voxel_mm);
    if (args.splat) plan.options.splat = *args.splat == "nearest" ? echo::Splat::nearest : echo::Splat::trilinear;
    if (args.compound)
        plan.options.compounding = *args.compound == "max"      ? echo::Compounding::max
                                   : *args.compound == "latest" ? echo::Compounding::latest
                                                                : echo::Compounding::mean;
    if (args.fill_holes) plan.fill_holes = *args.fill_holes == "on";
    if (args.grid) plan.plus_grid = *args.grid == "plus";
    // the configuration's fixed grid gives way to the command line's choice of grid or voxel
    if (args.grid && plan.extent) {
        plan.warnings.push_back(plan.extent_at + ": OutputOrigin and OutputExtent are not used: --grid " + *args.grid +
                                " makes the grid from the frames");
        plan.extent.reset();
    } else if (args.voxel_mm && plan.extent) {
        plan.warnings.push_back(plan.extent_at + ": OutputOrigin and OutputExtent are for the configuration's OutputSpacing; "
                                "with --voxel-mm the grid is made from the frames instead");
        plan.extent.reset();
    }
    plan.options.voxel_mm = std::min({plan.spacing.x, plan.spacing.y, plan.spacing.z});
    return plan;
}

const char* name_of(echo::Splat s) { return s == echo::Splat::nearest ? "nearest neighbour" : "trilinear"; }
const char* name_of(echo::Compounding c)
{
    return c == echo::Compounding::mean ? "mean" : c == echo::Compounding::max ? "maximum" : "latest";
}

// --budget-mb as bytes (unset: 4 GiB); nullopt (and said) when its bytes overflow 64 bits (where
// they used to wrap to a small or zero budget) or exceed the machine's memory.
std::optional<std::uint64_t> budget_bytes(std::optional<std::uint64_t> option)
{
    if (!option) return std::uint64_t(4096) << 20;
    const std::uint64_t mb = *option;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const std::uint64_t machine = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
    if (mb == 0) {
        std::fprintf(stderr, "echosim reconstruct: --budget-mb 0: the budget must be at least 1 MiB\n");
        return std::nullopt;
    }
    if (mb > (std::numeric_limits<std::uint64_t>::max() >> 20)) {
        std::fprintf(stderr, "echosim reconstruct: --budget-mb %llu: that many MiB overflow 64 bits of bytes\n",
                     static_cast<unsigned long long>(mb));
        return std::nullopt;
    }
    if (machine > 0 && (mb << 20) > machine) {
        std::fprintf(stderr, "echosim reconstruct: --budget-mb %llu: more than this machine's memory (%llu MiB)\n",
                     static_cast<unsigned long long>(mb), static_cast<unsigned long long>(machine >> 20));
        return std::nullopt;
    }
    return mb << 20;
}

// A configuration's transform that the recording holds too is not replaced unsaid (issue 34): the
// recording's is used, as resolve_sweep does, and each such transform is named.
void warn_also_recorded(Plan& plan, const ReconstructArgs& args, const io::PlusRecording& recording)
{
    io::TransformRepository config;
    std::map<std::pair<std::string, std::string>, const io::PlusConfigTransform*> by_frames;  // either way round
    for (const io::PlusConfigTransform& t : plan.config_transforms) {
        config.set(t.from, t.to, t.matrix, t.valid);
        by_frames[std::minmax(t.from, t.to)] = &t;
    }
    for (const io::AlsoRecorded& a : io::transforms_also_recorded(recording, config)) {
        const io::PlusConfigTransform& t = *by_frames.at(std::minmax(a.from, a.to));
        const int line = t.line;
        const std::string given = t.from + "To" + t.to;
        const std::string where = a.frames == 0 ? "file-wide" : "in " + std::to_string(a.frames) + " of its frames";
        plan.warnings.push_back(args.config.string() + ":" + std::to_string(line) + ": Transform: " + given + " is also in " +
                                args.sweep.string() + " (" + a.from + "To" + a.to + "Transform, " + where +
                                "): the recording's is used, the configuration's is not");
    }
}

std::filesystem::path labels_path(const std::filesystem::path& out)
{
    std::filesystem::path p = out;
    p.replace_filename(out.stem().string() + ".labels" + out.extension().string());
    return p;
}

// The files that writing `out` makes: the file itself and, for a detached MetaImage (.mhd), its
// data file beside it (io/metaimage.hpp).
std::vector<std::filesystem::path> written_files(const std::filesystem::path& out, bool compressed)
{
    std::vector<std::filesystem::path> files{out};
    if (io::text::lower(out.extension().string()) == ".mhd") files.push_back(std::filesystem::path(out).replace_extension(compressed ? ".zraw" : ".raw"));
    return files;
}

// Whether the outputs can be written as asked, checked before any work: each usable, none the
// same file as another or as an input (the sweep, its labels' sweep, the configuration).
bool outputs_checked(const ReconstructArgs& args)
{
    const std::filesystem::path label_sweep = label_sweep_path(args.sweep);
    std::error_code ec;
    const bool labelled = std::filesystem::exists(label_sweep, ec);
    std::vector<NamedPath> outputs;
    for (const auto& f : written_files(args.out, args.gzip)) outputs.push_back({f == args.out ? "--out" : "--out's data file", f});
    if (labelled)
        for (const auto& f : written_files(labels_path(args.out), true))
            outputs.push_back({f == labels_path(args.out) ? "--out's labels" : "--out's labels' data file", f});
    for (const NamedPath& o : outputs)
        if (!output_path_usable("reconstruct", o.option.c_str(), o.path)) return false;
    return outputs_distinct("reconstruct", outputs,
                            {{"--sweep", args.sweep}, {"--sweep's labels", labelled ? label_sweep : std::filesystem::path()}, {"--config", args.config}});
}

}  // namespace

int run_reconstruct(const ReconstructArgs& args)
{
    using clock = std::chrono::steady_clock;
    if (!outputs_checked(args)) return kExitBadInput;
    if (const std::string ext = io::text::lower(args.out.extension().string()); ext != ".nrrd" && ext != ".mha" && ext != ".mhd") {
        std::fprintf(stderr, "echosim reconstruct: --out %s: write a volume as .nrrd, .mha or .mhd\n", args.out.c_str());
        return kExitBadInput;
    }
    const std::optional<std::uint64_t> budget = budget_bytes(args.budget_mb);
    if (!budget) return kExitBadInput;
    Plan plan;
    io::Sweep sweep, labels;
    try {
        plan = make_plan(args);
        plan.options.memory_budget_bytes = *budget;
        io::PlusRecording recording = io::read_plus_recording(args.sweep);
        if (plan.reference_frame.empty())
            plan.reference_frame = args.config.empty() ? io::default_reference_frame(recording) : "Reference";
        if (plan.image_frame == plan.reference_frame) {
            std::fprintf(stderr,
                         "echosim reconstruct: the image frame and the reference frame are both %s: every frame would be "
                         "reconstructed at the identity, all in one plane (choose another --image-to-reference)\n",
                         printable(plan.image_frame).c_str());
            return kExitBadInput;
        }
        if (!args.config.empty()) warn_also_recorded(plan, args, recording);
        sweep = io::resolve_sweep(args.sweep, std::move(recording), plan.calibration, plan.image_frame, plan.reference_frame);
        if (std::filesystem::exists(label_sweep_path(args.sweep))) labels = io::read_plus_sequence(label_sweep_path(args.sweep));
    } catch (const std::runtime_error& e) {  // the file readers' errors, each naming its file and field
        std::fprintf(stderr, "echosim reconstruct: %s\n", printable(e.what()).c_str());
        return kExitBadInput;
    }
    // warnings quote the configuration's and the recording's names: escaped, as the readers' errors are
    for (const std::string& w : plan.warnings) std::fprintf(stderr, "echosim reconstruct: warning: %s\n", printable(w).c_str());
    const bool with_labels = labels.frames.size() == sweep.frames.size() && labels.width == sweep.width &&
                             labels.height == sweep.height && labels.pixel_type == io::VoxelType::uint8;

    std::vector<glm::dmat4> valid_transforms;
    std::size_t bad_images = 0, bad_transforms = 0;
    for (const io::TrackedFrame& f : sweep.frames) {
        if (f.valid) valid_transforms.push_back(f.image_to_reference);
        else if (!f.image_valid) ++bad_images;
        else ++bad_transforms;
    }
    if (bad_images + bad_transforms > 0)
        std::fprintf(stderr, "echosim reconstruct: %zu of %zu frames skipped: %zu with an image not OK, %zu with a transform not OK\n",
                     bad_images + bad_transforms, sweep.frames.size(), bad_images, bad_transforms);
    if (valid_transforms.empty()) {
        std::fprintf(stderr, "echosim reconstruct: %s: no frame has a valid image and transform\n", args.sweep.c_str());
        return kExitBadInput;
    }

    echo::ReconstructOptions& options = plan.options;
    options.output_type = sweep.pixel_type;  // the volume keeps the recording's values, as PLUS's does
    // what would give a collapsed or empty volume, refused before the work (issue 34)
    const std::optional<echo::PixelRect> kept = echo::clip_to_frame(options.clip, sweep.width, sweep.height);
    if (!kept) {
        std::fprintf(stderr,
                     "echosim reconstruct: %s: ClipRectangleOrigin %u %u lies outside the frames of %u x %u pixels: no pixel "
                     "would be pasted\n",
                     plan.clip_at.c_str(), options.clip.x0, options.clip.y0, sweep.width, sweep.height);
        return kExitBadInput;
    }
    if (options.clip.x1 != UINT32_MAX && (options.clip.x1 >= sweep.width || options.clip.y1 >= sweep.height))
        std::fprintf(stderr,
                     "echosim reconstruct: warning: %s: the clip rectangle reaches past the frames of %u x %u pixels: cut to them\n",
                     plan.clip_at.c_str(), sweep.width, sweep.height);
    options.clip = *kept;
    const double thickness = echo::sweep_thickness(valid_transforms, *kept);
    if (thickness <= 1e-6 * echo::frame_diagonal(valid_transforms, *kept)) {
        if (valid_transforms.size() == 1) {
            std::fprintf(stderr, "echosim reconstruct: %s: one frame has a valid image and transform: one plane spans no volume\n",
                         args.sweep.c_str());
            return kExitBadInput;
        }
        const bool same = std::all_of(valid_transforms.begin(), valid_transforms.end(),
                                      [&](const glm::dmat4& m) { return m == valid_transforms.front(); });
        std::fprintf(stderr,
                     "echosim reconstruct: %s: the %zu frames lie in one plane (%s): they span no volume; is %sTo%s the "
                     "transform meant?\n",
                     args.sweep.c_str(), valid_transforms.size(),
                     same ? "every frame has the same ImageToReference" : "they move only within it",
                     printable(plan.image_frame).c_str(), printable(plan.reference_frame).c_str());
        return kExitBadInput;
    }
    std::unique_ptr<echo::Reconstructor> r;
    try {
        echo::VoxelGrid grid;
        if (plan.extent) {
            const auto& e = *plan.extent;
            grid.spacing = plan.spacing;
            grid.origin = plan.origin + plan.spacing * glm::dvec3(e[0], e[2], e[4]);
            grid.size = {std::size_t(e[1] - e[0] + 1), std::size_t(e[3] - e[2] + 1), std::size_t(e[5] - e[4] + 1)};
        } else if (plan.plus_grid) {
            grid = echo::plus_grid(valid_transforms, sweep.width, sweep.height, options.clip, plan.spacing);
        } else {
            const echo::SweepBox box = echo::sweep_box(valid_transforms, sweep.width, sweep.height);
            const glm::dvec3 margin(options.voxel_mm);
            grid = echo::box_grid(box.lo - margin, box.hi + margin, options.voxel_mm, box.axes);
        }
        if (plan.extent && !echo::frames_reach(grid, valid_transforms, *kept)) {
            const glm::dvec3 far = grid.origin + grid.spacing * glm::dvec3(double(grid.size[0] - 1), double(grid.size[1] - 1),
                                                                          double(grid.size[2] - 1));
            const echo::VoxelGrid theirs = echo::plus_grid(valid_transforms, sweep.width, sweep.height, *kept, plan.spacing);
            const glm::dvec3 their_far = theirs.origin + theirs.spacing * glm::dvec3(double(theirs.size[0] - 1),
                                                                                   double(theirs.size[1] - 1), double(theirs.size[2] - 1));
            std::fprintf(stderr,
                         "echosim reconstruct: %s: the output grid of OutputOrigin and OutputExtent (%g %g %g to %g %g %g mm) is "
                         "reached by none of the %zu frames (they lie within %g %g %g to %g %g %g mm in %s)\n",
                         plan.extent_at.c_str(), grid.origin.x, grid.origin.y, grid.origin.z, far.x, far.y, far.z,
                         valid_transforms.size(), theirs.origin.x, theirs.origin.y, theirs.origin.z, their_far.x, their_far.y,
                         their_far.z, printable(plan.reference_frame).c_str());
            return kExitBadInput;
        }
        r = std::make_unique<echo::Reconstructor>(grid, options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim reconstruct: %s\n", printable(e.what()).c_str());
        return kExitBadInput;
    }
    const echo::VoxelGrid& grid = r->grid();
    std::printf("echosim reconstruct: %s interpolation, %s compounding, holes %s; %s grid %zux%zux%zu of %g x %g x %g mm in %s\n",
                name_of(options.splat), name_of(options.compounding), plan.fill_holes ? "filled" : "left empty",
                plan.extent ? "the configuration's" : plan.plus_grid ? "PLUS's" : "a sweep-aligned", grid.size[0], grid.size[1],
                grid.size[2], grid.spacing.x, grid.spacing.y, grid.spacing.z,
                printable(plan.reference_frame).c_str());

    TerminalProgress progress("echosim reconstruct: ");
    const std::string inserting = "inserting the frames (" + std::to_string(valid_transforms.size()) + ")";
    const auto t0 = clock::now();
    std::size_t inserted = 0;
    for (std::size_t f = 0; f < sweep.frames.size(); ++f) {
        if (!sweep.frames[f].valid) continue;
        const echo::FramePixels px{{sweep.frame_pixels(f), sweep.frame_bytes()}, sweep.pixel_type, sweep.width, sweep.height};
        const std::span<const std::uint8_t> lb = with_labels ? std::span<const std::uint8_t>(labels.frame_pixels(f), labels.frame_bytes())
                                                             : std::span<const std::uint8_t>();
        r->insert(px, lb, sweep.frames[f].image_to_reference);
        ++inserted;
        progress(inserting, double(inserted) / double(valid_transforms.size()));
    }
    const double insert_s = std::chrono::duration<double>(clock::now() - t0).count();
    if (r->filled_voxels() == 0) {
        progress.finish();
        std::fprintf(stderr,
                     "echosim reconstruct: no pixel of the %zu frames landed in the grid (outside it, or below the pixel "
                     "rejection threshold): nothing written\n",
                     inserted);
        return kExitBadInput;
    }
    const double covered = double(r->filled_voxels()) / double(r->voxel_count());
    int passes = 0;
    double fill_s = 0;
    if (plan.fill_holes) {
        const auto t1 = clock::now();
        passes = r->fill_holes([&](double done) { progress("filling the holes", done); });
        fill_s = std::chrono::duration<double>(clock::now() - t1).count();
    }
    progress.finish();

    io::Volume volume = r->volume();
    volume.key_values["echosim_source"] = args.sweep.filename().string();
    io::Volume label_map;
    if (with_labels) {
        label_map = r->labels();
        for (int t = 0; t < echo::kTissueCount; ++t) label_map.key_values["label_" + std::to_string(t)] = echo::tissue_name(echo::Tissue(t));
    }
    // the volume and its labels stay a pair: both written, or neither replaced
    const std::filesystem::path lp = labels_path(args.out);
    try {
        std::vector<std::filesystem::path> outputs{args.out};
        if (with_labels) outputs.push_back(lp);
        write_together(outputs, [&](std::size_t i, const std::filesystem::path& path) {
            if (i == 0) io::write_volume(path, volume, args.gzip);
            else io::write_volume(path, label_map, true);
        });
    } catch (const std::runtime_error& e) {
        std::fprintf(stderr, "echosim reconstruct: %s (nothing written; files already there are as they were)\n", e.what());
        return kExitFailure;
    }
    // an earlier run's labels beside the new volume could be taken for its own; they are not this
    // command's to delete, so it says so
    std::error_code ec;
    if (!with_labels && std::filesystem::exists(lp, ec))
        std::fprintf(stderr, "echosim reconstruct: warning: %s is not this volume's labels (the sweep has none); left as it was\n",
                     lp.c_str());
    std::printf("echosim reconstruct: %zux%zux%zu voxels (%llu MiB while working) in %s\n", volume.size[0], volume.size[1],
                volume.size[2], static_cast<unsigned long long>(r->memory_bytes() >> 20), args.out.c_str());
    std::printf("echosim reconstruct: %zu frames in %.2f s (%.0f frames/s), %.1f %% of voxels hit", inserted, insert_s,
                double(inserted) / insert_s, 100 * covered);
    if (plan.fill_holes)
        std::printf(", %.1f %% after filling holes (%d passes, %.2f s)", 100.0 * double(r->filled_voxels()) / double(r->voxel_count()),
                    passes, fill_s);
    std::printf("\n");
    if (with_labels) std::printf("echosim reconstruct: labels in %s\n", lp.c_str());
    return kExitOk;
}

}  // namespace echosim::app

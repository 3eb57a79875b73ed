// `echosim slice`: one echographic image at a probe pose, pressed by the simulated tissue if asked
// (DESIGN.md §4), on the GPU or with --cpu on the CPU twin; PNG to look at, NRRD placed in the
// volume's space for 3D Slicer.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>

#include "app/commands.hpp"
#include "app/gpu_args.hpp"
#include "app/terminal_progress.hpp"
#include "app/volume_source.hpp"
#include "echo/echo_image_cpu.hpp"
#include "echo/kernel_params.hpp"
#include "echo/volume_placement.hpp"
#include "gpu/context.hpp"
#include "image/echo_image_gpu.hpp"
#include "io/png.hpp"
#include "session/session.hpp"

namespace echosim::app {
namespace {

// The image as NRRD in the volume's space: sizes W H 1, the pixel steps along the probe's lateral
// and beam axes, the elevational axis scaled by the volume's smallest voxel (a slice that thick).
io::Volume image_volume(const echo::EchoImage& image, const echo::ImagePlane& plane, const Pose& face, const io::Volume& grid)
{
    io::Volume v = io::make_volume({image.columns, image.rows, 1}, io::VoxelType::uint8);
    for (std::size_t i = 0; i < image.rgba.size(); ++i) v.data[i] = std::uint8_t(image.rgba[i] & 0xffu);
    const double thickness = grid.finest_spacing_mm();
    const glm::dmat4 to_world = echo::pixel_to_world(plane, face);
    v.directions = glm::dmat3(glm::dvec3(to_world[0]), glm::dvec3(to_world[1]), glm::dvec3(to_world[2]) * thickness);
    v.origin = glm::dvec3(to_world[3]);
    return v;
}

io::RgbaImage to_png_image(const echo::EchoImage& image)
{
    io::RgbaImage png;
    png.width = image.columns;
    png.height = image.rows;
    png.pixels.resize(std::size_t(image.columns) * image.rows * 4);
    std::memcpy(png.pixels.data(), image.rgba.data(), png.pixels.size());
    return png;
}

}  // namespace

int run_slice(const SliceArgs& args)
{
    const auto fail = [](const std::string& what) {
        std::fprintf(stderr, "echosim slice: %s\n", what.c_str());
        return kExitBadInput;
    };
    const std::string ext = args.out.extension().string();
    if (ext != ".png" && ext != ".nrrd") return fail("--out " + args.out.string() + ": write a .png or a .nrrd");
    if (!output_path_usable("slice", "--out", args.out) ||
        !outputs_distinct("slice", {{"--out", args.out}}, {{"--volume", args.volume}, {"--labels", args.labels}, {"--model", args.model}}))
        return kExitBadInput;
    if (args.press_mm >= 0 && args.force_n >= 0) return fail("--press-mm and --force: give one or the other");
    if (args.volume.empty() && !args.labels.empty()) return fail("--labels " + args.labels.string() + ": give the --volume they label");
    if (args.press_mm > session::Session::kMaxPressMm || !std::isfinite(args.press_mm))
        return fail("--press-mm " + std::to_string(args.press_mm) + ": must be in 0.." + std::to_string(session::Session::kMaxPressMm));

    session::SessionOptions options;
    echo::Imaging imaging = echo::Imaging::interpolative;
    if (!read_model_option("slice", args.model, options.tissue)) return kExitBadInput;
    try {
        options.image = echo::plane_with_pixel(args.width_mm, args.depth_mm, args.pixel_mm);
        options.patient.which = echo::parse_case(args.case_name);
        imaging = echo::parse_imaging(args.imaging);
    } catch (const std::invalid_argument& e) {
        return fail(e.what());
    }
    options.patient.venous_pressure_mmHg = args.venous_mmhg;
    options.patient.heart_rate_bpm = args.heart_rate_bpm;

    VolumePair volumes;
    TerminalProgress progress(std::string("echosim slice: ") + kCaseVolumeProgress);
    try {
        if (args.volume.empty())
            volumes = case_volume(options.patient.which, progress, args.coarse);
        else
            volumes = user_volume(args.volume, args.labels);
    } catch (const std::exception& e) {
        progress.finish();
        return fail(e.what());
    }
    progress.finish();
    if (imaging == echo::Imaging::generative && !volumes.labels)
        return fail("--imaging generative: " + volumes.description + " has no tissue labels to synthesise from (give --labels)");

    session::Session session(options);
    session::SettleReport settle;  // none: resting on the skin
    try {
        Pose rest = args.pose.empty() ? session.probe().rest : parse_pose(args.pose);
        // a user's volume need not lie in our leg's space: where the exam patch's centre misses
        // most of it, the default is the volume's own middle, and the pose is said
        if (args.pose.empty() && !args.volume.empty()) {
            const Pose on_volume = echo::pose_on_volume(*volumes.volume);
            if (const double coverage = echo::plane_coverage(*volumes.volume, options.image, rest);
                coverage < 0.5 && echo::plane_coverage(*volumes.volume, options.image, on_volume) > coverage) {
                rest = on_volume;
                std::printf("echosim slice: the exam patch's centre misses %s: sliced on the volume's middle instead, --pose %s\n",
                            args.volume.c_str(), format_pose(rest).c_str());
            }
        }
        session.place_probe({rest, 0.0});
        // press_to_force leaves the tissue settled at the press it found
        if (args.force_n >= 0)
            settle = session.press_to_force(rest, args.force_n);
        else if (args.press_mm > 0)
            if (settle = session.press_and_settle(rest, args.press_mm); !settle.settled)
                throw std::runtime_error(session::not_settled_message(args.press_mm, settle));
    } catch (const std::invalid_argument& e) {
        return fail(std::string(args.force_n >= 0 ? "--force: " : "--pose: ") + e.what());
    } catch (const std::runtime_error& e) {
        std::fprintf(stderr, "echosim slice: %s\n", e.what());
        return kExitFailure;
    }
    const session::SessionView& view = session.view();
    echo::EchoFrame frame = *view.echo;
    frame.time_s = args.time_s;  // the heart's phase the user asked for, not the settle's
    // a plane that misses the volume would image nothing but black: not an answer
    const double coverage = echo::plane_coverage(*volumes.volume, options.image, frame.face);
    if (coverage == 0)
        return fail("the image plane at --pose " + format_pose(frame.face) + " misses " + volumes.description +
                    " entirely: nothing written (give a --pose on the volume)");
    if (!(view.press_mm > 0)) frame.columns.clear();  // resting on the skin: the undeformed image
    echo::ScannerSettings scanner;
    scanner.gain_db = args.gain_db;
    scanner.dynamic_range_db = args.dynamic_range_db;
    scanner.markers = ext == ".png";  // NRRD keeps exact values

    const auto start = std::chrono::steady_clock::now();
    echo::EchoImage image;
    std::string device = "the CPU twin";
    std::uint32_t messages = 0;
    if (args.cpu) {
        image = echo::render_echo_cpu(*volumes.volume, volumes.labels.get(), options.image, frame, scanner, options.patient, false, imaging);
    } else {
        std::shared_ptr<const std::atomic<std::uint32_t>> counter;
        {
            gpu::Context ctx(context_options(args.gpu));
            counter = ctx.validation_counter();
            gpu::CommandPool pool(ctx);
            auto gpu_volume = std::make_shared<const image::EchoVolumeGpu>(
                pool, *volumes.volume, volumes.labels.get(), image::GreyLayout::best,
                imaging == echo::Imaging::generative ? image::LabelTexels::make : image::LabelTexels::none);
            image::EchoImageGpu pipeline(ctx, gpu_volume, options.image, options.patient, image::DeformReads::best, imaging);
            pipeline.scanner() = scanner;
            image = pipeline.render(pool, frame);
            device = ctx.device_name();
        }
        messages = counter->load();
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (ext == ".png")
        io::write_png(args.out, to_png_image(image));
    else
        io::write_nrrd(args.out, image_volume(image, options.image, frame.face, *volumes.volume), true);
    std::printf("echosim slice: %ux%u image of %s on %s in %.0f ms, written to %s\n", image.columns, image.rows, volumes.description.c_str(),
                device.c_str(), ms, args.out.c_str());
    if (coverage < 0.995)
        std::printf("echosim slice: %.0f %% of the image lies outside the volume (black there)\n", 100 * (1 - coverage));
    if (view.press_mm > 0)
        std::printf("echosim slice: probe pressed %.1f mm, tissue pushes back %.2f N (ripple +/- %.2f N; %.1f kPa over the face)\n",
                    settle.press_mm, settle.force_N, settle.ripple_N, frame.skin_pressure_kpa);
    if (messages > 0) {
        std::fprintf(stderr, "echosim slice: Vulkan validation reported %u message(s)\n", messages);
        return kExitValidation;
    }
    return kExitOk;
}

}  // namespace echosim::app

// echosim: one binary, one subcommand per job (DESIGN.md §4).
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/cmd_records.hpp"
#include "core/image_limits.hpp"
#include "app/soak.hpp"
#include "igtl/live_frame.hpp"

namespace {

void add_gpu_options(CLI::App* cmd, echosim::app::GpuArgs& gpu)
{
    cmd->add_option("--gpu", gpu.gpu, "Vulkan device to use: part of its name, or cpu/lavapipe, discrete, integrated (else ECHOSIM_GPU)");
    cmd->add_flag("--validation", gpu.validation, "enable the Khronos validation layer; any message makes the command fail");
}

// CLI::Range lets NaN through (every comparison with it is false) and, given "inf", compares an
// infinity: a range that refuses both by name, for every number the command line takes.
CLI::Validator finite_range(double lo, double hi)
{
    const std::string range = "[" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]";
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a number";
            if (!std::isfinite(v)) return "'" + text + "' is not a finite number";
            if (v < lo || v > hi) return "Value " + text + " not in range " + range;
            return {};
        },
        "NUMBER in " + range);
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace echosim::app;
    // a file-size limit reached (ulimit -f) is a write error naming the file, as a full disk is,
    // not a kill that would leave a half-written temporary file behind
    std::signal(SIGXFSZ, SIG_IGN);
    // a log redirected to a file gets each line as it is printed, so a kiosk stopped or killed
    // keeps every line up to then (stdout to a file is otherwise written in 4 KiB blocks)
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    CLI::App app{"echosim: real-time echographic simulator with force feedback", "echosim"};
    app.set_version_flag("--version", std::string("echosim ") + ECHOSIM_VERSION);
    app.require_subcommand(1);

    RenderArgs render;
    auto* render_cmd = app.add_subcommand("render", "render one frame headless to a PNG");
    render_cmd->add_option("--out", render.out, "PNG file to write")->required();
    render_cmd->add_option("--width", render.width, "image width [px]; at most 8192 a side and 7680x4320 in all")
        ->check(finite_range(16u, echosim::kMaxImageSide));
    render_cmd->add_option("--height", render.height, "image height [px]")->check(finite_range(16u, echosim::kMaxImageSide));
    render_cmd->add_option("--pose", render.pose, "probe pose x,y,z,qw,qx,qy,qz in world (LPS mm)");
    render_cmd->add_option("--model", render.model, "tissue model JSON, as `echosim fit` writes it (default: the shipped thigh)");
    render_cmd->add_option("--press-mm", render.press_mm, "press the probe this far into the skin and let the tissue settle [mm]")
        ->check(finite_range(0.0, 30.0));
    render_cmd->add_option("--camera", render.camera,
                           "orbit camera yaw,pitch [rad],distance [mm] and optionally its target x,y,z [mm]; "
                           "target 'probe' looks at the probe");
    add_gpu_options(render_cmd, render.gpu);

    RunArgs run;
    auto* run_cmd = app.add_subcommand("run", "the simulator in a window");
    run_cmd->add_option("--width", run.width, "window width [px]");
    run_cmd->add_option("--height", run.height, "window height [px]");
    run_cmd->add_flag("--fullscreen", run.fullscreen, "start fullscreen (F11 toggles)");
    run_cmd->add_option("--frames", run.frames, "quit after this many presented frames")->check(CLI::NonNegativeNumber);
    run_cmd->add_flag("--exercise", run.exercise, "resize, minimise and toggle fullscreen while running (smoke test)");
    run_cmd->add_option("--volume", run.volume, "echographic volume (NRRD or MetaImage; not 8-bit: min..max mapped onto 0..255); default: the case's, made once and cached");
    run_cmd->add_option("--labels", run.labels, "tissue labels on the volume's grid (NRRD or MetaImage, codes 0..255); without: linear deformation");
    run_cmd->add_option("--model", run.model, "tissue model JSON, as `echosim fit` writes it (default: the shipped thigh)");
    run_cmd->add_option("--case", run.case_name, "the case the start screen chooses: a shipped case's id (echosim case list), or random");
    run_cmd->add_option("--imaging", run.imaging,
                        "how the echographic image is made: interpolative (sliced from the case's reconstructed volume, deformed) or generative "
                          "(synthesised each frame from the case's anatomy where the pressed tissue rests; needs labels); default: as the case says")
        ->check(CLI::IsMember({"interpolative", "generative"}));
    run_cmd->add_option("--device", run.device,
                        "what moves the probe: mouse (and keyboard), spacemouse (3Dconnexion, hot-plugged), openhaptics (a 3D Systems "
                        "Touch/Phantom arm, force feedback), simulated-arm (a simulated hand on a simulated arm, force feedback), null")
        ->check(CLI::IsMember({"mouse", "spacemouse", "openhaptics", "simulated-arm", "null"}));
    run_cmd->add_option("--trajectory", run.trajectory, "play this trajectory CSV (t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz) instead of a device");
    const std::string igtl_port = std::to_string(echosim::igtl::kDefaultPort);
    run_cmd->add_option("--igtl", run.igtl_port,
                        "also serve the live image and the probe over OpenIGTLink on PORT (1..65535; without PORT: " + igtl_port +
                            ", PlusServer's), for 3D Slicer")
        ->expected(0, 1)
        ->default_str(igtl_port)
        ->type_name("[PORT]");
    run_cmd->add_option("--igtl-bind", run.igtl_bind,
                        "with --igtl: listen on this address, an IPv4 or IPv6 literal (0.0.0.0 or :: for every interface, so 3D Slicer on "
                        "another machine can connect; the link has no authentication); default: the loopback interface, this machine alone")
        ->type_name("ADDRESS");
    run_cmd->add_flag("--kiosk", run.kiosk,
                      "the skills lab's kiosk: fullscreen at the display's resolution (up to 3840x2160), the UI scaled to be read "
                      "standing, Esc does not quit (Ctrl+Alt+Q does), an idle lesson scored, stored and the start screen shown again");
    run_cmd->add_option("--idle-timeout", run.idle_timeout_s, "with --kiosk: seconds without input before an idle lesson is stored (0: never)")
        ->check(finite_range(0.0, 86400.0));
    run_cmd->add_option("--records", run.records, "the trainee records database (SQLite; default: the user's data folder)");
    run_cmd->add_flag("--coarse", run.coarse, "the cases' volumes at 0.6 mm (seconds to make: tests, slow machines)");
    run_cmd->footer(echosim::app::run_keys_help());
    add_gpu_options(run_cmd, run.gpu);

    MeasureArgs measure;
    auto* measure_cmd = app.add_subcommand("measure", "simulate the force-displacement campaign on the reference thigh (synthetic measurements CSV)");
    measure_cmd->add_option("--out", measure.out, "CSV file to write")->required();
    measure_cmd->add_option("--seed", measure.seed, "random seed of the sensor noise and leg motion");

    FitArgs fit;
    auto* fit_cmd = app.add_subcommand("fit", "fit the two-layer tissue model to force-displacement measurements");
    fit_cmd->add_option("--data", fit.data, "measurements CSV (point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N)")->required();
    fit_cmd->add_option("--out", fit.out, "tissue model JSON to write")->required();
    fit_cmd->add_option("--report", fit.report, "folder for the report: statistics and plots");
    fit_cmd->add_option("--method", fit.method, "lm (Levenberg-Marquardt) or steepest (the paper's steepest descent)")
        ->check(CLI::IsMember({"lm", "steepest"}));
    fit_cmd->add_flag("--json", fit.json, "print a JSON summary on stdout");

    PhantomArgs phantom;
    auto* phantom_cmd = app.add_subcommand("phantom", "a tracked B-mode sweep of the thigh phantom, as a PLUS sequence file");
    phantom_cmd->add_option("--case", phantom.case_name, "healthy, dvt-acute or dvt-chronic");
    phantom_cmd->add_option("--out", phantom.out, "sweep to write (.mha); its frames' labels go beside it (.labels.mha)")->required();
    phantom_cmd->add_option("--labels", phantom.labels, "also write the phantom's label map (NRRD, 0.3 mm)");
    phantom_cmd->add_option("--frames", phantom.frames, "frames in the sweep")->check(finite_range(2, 5000));
    phantom_cmd->add_option("--pixel-mm", phantom.pixel_mm, "image pixel size [mm]")->check(finite_range(0.02, 1.0));
    phantom_cmd->add_option("--seed", phantom.seed, "random seed of the hand tremor");
    phantom_cmd->add_flag("--compressed", phantom.compressed, "zlib-compress the pixels");
    phantom_cmd->add_flag("--cpu", phantom.cpu, "synthesise the frames on the CPU (default: the GPU, falling back to the CPU without a device)");
    add_gpu_options(phantom_cmd, phantom.gpu);

    ReconstructArgs reconstruct;
    auto* reconstruct_cmd = app.add_subcommand("reconstruct", "freehand 3D reconstruction of a tracked sweep (PLUS recording) into a volume");
    reconstruct_cmd->add_option("--sweep", reconstruct.sweep, "PLUS sequence (.mha, .igs.mha, .seq.nrrd, .igs.nrrd)")->required();
    reconstruct_cmd->add_option("--out", reconstruct.out, "volume to write (.nrrd or .mha); labels beside it when the sweep has them")->required();
    reconstruct_cmd->add_option("--config", reconstruct.config,
                                "PLUS device-set configuration (.xml): its CoordinateDefinitions and VolumeReconstruction element");
    reconstruct_cmd->add_option("--image-to-reference", reconstruct.image_to_reference,
                                "the frame to reconstruct in (e.g. Reference, Tracker), or a transform name such as ImageToTracker");
    reconstruct_cmd->add_option("--voxel-mm", reconstruct.voxel_mm, "voxel size [mm] (overrides OutputSpacing)")->check(finite_range(0.02, 10.0));
    reconstruct_cmd->add_option("--splat", reconstruct.splat, "nearest or trilinear (PLUS: NEAREST_NEIGHBOR or LINEAR)")
        ->check(CLI::IsMember({"nearest", "trilinear"}));
    reconstruct_cmd->add_option("--compound", reconstruct.compound, "mean, max or latest (PLUS: MEAN, MAXIMUM, LATEST)")
        ->check(CLI::IsMember({"mean", "max", "latest"}));
    reconstruct_cmd->add_option("--fill-holes", reconstruct.fill_holes, "on or off (default: on, or the configuration's FillHoles)")
        ->check(CLI::IsMember({"on", "off"}));
    reconstruct_cmd->add_option("--grid", reconstruct.grid,
                                "plus: PLUS's output grid, axis-aligned in the reference frame; sweep: a box aligned with the sweep "
                                "(default: plus with --config, else sweep)")
        ->check(CLI::IsMember({"plus", "sweep"}));
    reconstruct_cmd->add_option("--budget-mb", reconstruct.budget_mb, "refuse volumes that need more memory [MiB]")
        ->check(CLI::Validator(  // a whole number that fits 64 bits: "-1" and 2^64 would wrap or saturate unsaid
            [](std::string& s) {
                std::uint64_t v = 0;
                const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
                if (s.empty() || end != s.data() + s.size() || s.front() == '-') return "'" + s + "' is not a whole number of MiB";
                return ec == std::errc() ? std::string() : "'" + s + "' MiB overflow 64 bits";
            },
            "MiB"));
    reconstruct_cmd->add_flag("--gzip", reconstruct.gzip, "compress the volume's voxels");

    BenchArgs bench;
    auto* bench_cmd = app.add_subcommand("bench", "run the benchmarks and print a table");
    bench_cmd->add_option("names", bench.names, "benchmarks to run (default: all)");
    bench_cmd->add_option("--json", bench.json, "also write the results as JSON to this file");
    bench_cmd->add_option("--min-time", bench.min_time_s, "seconds each measurement runs at least")->check(CLI::PositiveNumber);
    bench_cmd->add_option("--repetitions", bench.repetitions,
                          "run each row this many times and report its median, with the least and greatest rates (a shared machine's spread)")
        ->check(CLI::Range(1, 100));
    bench_cmd->add_option("--filter", bench.filter, "run only the rows whose name matches this regular expression (e.g. 'physics/50625/')");
    add_gpu_options(bench_cmd, bench.gpu);

    SliceArgs slice;
    auto* slice_cmd = app.add_subcommand("slice", "one echographic image at a probe pose, pressed by the simulated tissue if asked");
    slice_cmd->add_option("--volume", slice.volume, "volume (NRRD or MetaImage; not 8-bit: min..max mapped onto 0..255); default: the case's volume, made once and cached");
    slice_cmd->add_option("--labels", slice.labels, "tissue labels on the volume's grid (NRRD or MetaImage, codes 0..255); without: linear deformation");
    slice_cmd->add_option("--out", slice.out, "image to write: .png, or .nrrd placed in the volume's space")->required();
    slice_cmd->add_option("--pose", slice.pose, "probe resting on the skin: x,y,z,qw,qx,qy,qz in world (LPS mm); default: the patch centre");
    slice_cmd->add_option("--model", slice.model, "tissue model JSON, as `echosim fit` writes it (default: the shipped thigh)");
    slice_cmd->add_option("--press-mm", slice.press_mm, "press the probe this far in and let the tissue settle [mm]")
        ->check(finite_range(0.0, 25.0));
    slice_cmd->add_option("--force", slice.force_n, "press the probe until the tissue pushes back this hard [N]")
        ->check(finite_range(0.01, 1000.0));
    slice_cmd->add_flag("--cpu", slice.cpu, "run the CPU twin of the kernels instead of the GPU");
    slice_cmd->add_option("--imaging", slice.imaging,
                          "interpolative (slice the volume, deformed) or generative (synthesise the B-mode image of the labels' tissue where "
                          "the pressed tissue rests; needs labels)")
        ->check(CLI::IsMember({"interpolative", "generative"}));
    slice_cmd->add_option("--case", slice.case_name, "healthy, dvt-acute or dvt-chronic (the vessels' behaviour, and the default volume)");
    slice_cmd->add_flag("--coarse", slice.coarse, "the case's default volume at 0.6 mm, in seconds to make (a quick look, tests); with --volume: nothing");
    slice_cmd->add_option("--width-mm", slice.width_mm, "image width [mm]")->check(finite_range(1.0, 200.0));
    slice_cmd->add_option("--depth-mm", slice.depth_mm, "image depth [mm]")->check(finite_range(1.0, 300.0));
    slice_cmd->add_option("--pixel-mm", slice.pixel_mm, "pixel size [mm]")->check(finite_range(0.005, 5.0));
    slice_cmd->add_option("--gain-db", slice.gain_db, "overall gain [dB]")->check(finite_range(-60.0, 60.0));
    slice_cmd->add_option("--dynamic-range-db", slice.dynamic_range_db, "display dynamic range [dB]")->check(finite_range(10.0, 120.0));
    slice_cmd->add_option("--venous-mmhg", slice.venous_mmhg, "venous pressure [mmHg]")->check(finite_range(0.0, 100.0));
    slice_cmd->add_option("--heart-rate", slice.heart_rate_bpm, "heart rate [beats/min] (0: no pulse)")->check(finite_range(0.0, 250.0));
    slice_cmd->add_option("--time", slice.time_s, "moment of the heart cycle [s from a diastole]")->check(finite_range(0.0, 1e6));
    add_gpu_options(slice_cmd, slice.gpu);

    HapticsDemoArgs demo;
    auto* demo_cmd = app.add_subcommand("haptics-demo",
                                        "the paper's Fig. 8: the force while the probe slides across the skin, with and without the local contact model");
    demo_cmd->add_option("--out", demo.out, "folder for force_log.csv, force.png and summary.json")->required();
    demo_cmd->add_option("--physics-hz", demo.physics_hz, "the physics' rate (the paper's: 100 Hz); the haptic loop runs at 1 kHz")
        ->check(finite_range(10.0, 1000.0));
    demo_cmd->add_flag("--json", demo.json, "print the summary as JSON on stdout");
    SoakArgs soak;
    auto* soak_cmd = app.add_subcommand(
        "soak",
        "a long scripted session, headless: the probe pressing and sliding across the thigh in a loop, the physics and the 1 kHz "
        "haptic loop on the real-time clock, the echographic image and the scene rendered offscreen every frame, validation on. "
        "Passes when resident memory is flat after the warm-up (the script's first round, 7.2 s, or a quarter of the run, "
        "whichever is longer, at most 30 s): end - start <= 4 MiB and "
        "the fitted line's rise <= 4 MiB; no validation message; haptic period error p99 <= 0.1 ms (over the whole run, and over "
        "the seconds in which the host took no CPU time, /proc/stat's steal) and no missed deadline (> 1 ms late), as --deadlines "
        "says. Exit 0 passed, 1 a bound not held, 3 validation messages");
    soak_cmd->add_option("--seconds", soak.seconds, "how long the session runs [s] (CI: 120; by hand: 600)")
        ->check(finite_range(kSoakMinSeconds, 86400.0));
    soak_cmd->add_option("--json", soak.json, "also write the report as JSON to this file");
    soak_cmd->add_option("--width", soak.width, "offscreen frame width [px]")->check(finite_range(64u, 7680u));
    soak_cmd->add_option("--height", soak.height, "offscreen frame height [px]")->check(finite_range(64u, 4320u));
    soak_cmd->add_option("--deadlines", soak.deadlines,
                         "which deadline bounds fail the run: strict (both p99s and misses), p99 (the p99 over the seconds free of host "
                         "steal; the whole run's and the misses reported only), report (none)")
        ->check(CLI::IsMember({"strict", "p99", "report"}));
    add_gpu_options(soak_cmd, soak.gpu);
    DevicesArgs devices;
    auto* devices_cmd = app.add_subcommand("devices", "list the input and haptic devices echosim can drive, and whether each is ready");
    devices_cmd->add_flag("--json", devices.json, "print them as a JSON array");
    CaseArgs case_args;
    auto* case_cmd = app.add_subcommand("case", "check the exam's case files (assets/cases/README.md) and list the shipped cases");
    case_cmd->require_subcommand(1);
    case_cmd->add_subcommand("validate", "read each case file as the exam does: 'F: ok (id, N stations, protocol)', or the field at fault (exit 2)")
        ->callback([&case_args] { case_args.action = "validate"; })
        ->add_option("files", case_args.files, "case files (JSON, assets/cases/scenario.schema.json)")
        ->required();
    case_cmd->add_subcommand("list", "the shipped cases: id and title")->callback([&case_args] { case_args.action = "list"; });
    CasePlanArgs plan_args;
    auto* plan_cmd = case_cmd->add_subcommand(
        "plan", "write a case's scripted exam: the correct one, or one making a classic error at one station, each station pressed "
                "into the case's adequate force band on the simulated tissue");
    auto* plan_scenario = plan_cmd->add_option("--scenario", plan_args.scenario, "a case file");
    plan_cmd->add_option("--case", plan_args.case_id, "a shipped case's id")->excludes(plan_scenario);
    plan_cmd->add_option("--style", plan_args.style, "correct, skip, light-press, oblique, artery, excessive or mimic-called");
    plan_cmd->add_option("--at", plan_args.at, "the station (from 0) the error happens at (default: one that fits it)");
    auto* plan_out = plan_cmd->add_option("--out", plan_args.out, "the script (CSV)");
    plan_cmd->add_option("--all", plan_args.all, "every shipped case's correct exam and errors, into this folder")->excludes(plan_out);
    plan_cmd->callback([&case_args] { case_args.action = "plan"; });

    ExamArgs exam_args;
    auto* exam_cmd = app.add_subcommand(
        "exam",
        "a scripted compression exam, headless and repeatable to the byte: the case's probe script played on simulated time, every "
        "station scored from the simulation's truth; writes frames, the image at each station's deepest press, force.csv, "
        "report.json, report.html and summary.png into --out, and stores the exam in the trainee records");
    auto* exam_scenario = exam_cmd->add_option("--scenario", exam_args.scenario, "a case file (assets/cases/README.md)");
    exam_cmd->add_option("--case", exam_args.case_id, "a shipped case's id (echosim case list), or random")->excludes(exam_scenario);
    exam_cmd->add_option("--seed", exam_args.seed, "--case random's draw");
    exam_cmd->add_option("--trajectory", exam_args.trajectory,
                         "the exam's script: a trajectory CSV with an optional last column 'call' (compressible, not-compressible); "
                         "default: the case's shipped correct exam");
    exam_cmd->add_option("--out", exam_args.out, "the report's folder")->required();
    exam_cmd->add_option("--frames-per-s", exam_args.frames_per_s, "frames written per simulated second (0: images at the stations only, made on the CPU: nothing drawn, no volume on the GPU)");
    exam_cmd->add_option("--trainee", exam_args.trainee, "the trainee's name, for the records");
    exam_cmd->add_option("--records", exam_args.records, "the trainee records database (default: in the user's data folder)");
    exam_cmd->add_flag("--no-records", exam_args.no_records, "do not store the exam in the records");
    exam_cmd->add_flag("--coarse", exam_args.coarse, "make the case's volume at 0.6 mm, in seconds (tests, benchmarks)");
    exam_cmd->add_option("--imaging", exam_args.imaging,
                         "how the echographic image is made: interpolative (sliced from the case's reconstructed volume, deformed) or generative "
                          "(synthesised each frame from the case's anatomy where the pressed tissue rests; needs labels); default: as the case says")
        ->check(CLI::IsMember({"interpolative", "generative"}));
    add_gpu_options(exam_cmd, exam_args.gpu);

    RecordsArgs records_args;
    auto* records_cmd = app.add_subcommand(
        "records", "the trainee records: the exams stored, and each trainee's learning curve (score per session, CUSUM per station type)");
    const auto records_source = [&records_args](CLI::App* cmd) {
        cmd->add_option_function<std::string>(
            "--trainee", [&records_args](const std::string& name) { records_args.trainee = name; }, "only this trainee's sessions");
        cmd->add_option("--records", records_args.records,
                        "the records database (default: $XDG_DATA_HOME/echosim/records.sqlite, else ~/.local/share/echosim/records.sqlite)");
    };
    records_source(records_cmd);
    records_cmd->add_option("--plot", records_args.plot, "also draw the learning curves into this PNG");
    records_cmd->add_flag("--json", records_args.json, "print the sessions and the learning curves as JSON");
    auto* records_export_cmd =
        records_cmd->add_subcommand("export", "write the sessions as xAPI 1.0.3 statements, for a learning record store to import");
    records_export_cmd->add_option("--xapi", records_args.xapi, "the JSON file of statements to write")->required();
    records_source(records_export_cmd);
    records_export_cmd->add_option("--homepage", records_args.homepage, "the home page of the trainees' accounts: the lab's (default: https://echosim.org)");
    auto* records_add_cmd = records_cmd->add_subcommand(
        "add", "store an exam's report.json in the records (an exam run with --no-records, or on another machine)");
    records_add_cmd->add_option("report", records_args.report, "the exam's report.json")->required();
    records_source(records_add_cmd);

    // a bare `echosim` is someone finding out what it does: its help, not an error
    if (argc == 1) {
        std::fputs(app.help().c_str(), stdout);
        return kExitOk;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help is no error; every other parse error (a value out of range, an unknown option, a
        // missing one) is bad input, exit 2 as documented, not CLI11's own codes (105, 106, ...)
        return app.exit(e) == 0 ? kExitOk : kExitBadInput;
    }

    const char* which = app.get_subcommands().front()->get_name().c_str();
    try {
        if (render_cmd->parsed()) return run_render(render);
        if (slice_cmd->parsed()) return run_slice(slice);
        if (run_cmd->parsed()) return run_window(run);
        if (bench_cmd->parsed()) return run_bench(bench);
        if (measure_cmd->parsed()) return run_measure(measure);
        if (fit_cmd->parsed()) return run_fit(fit);
        if (phantom_cmd->parsed()) return run_phantom(phantom);
        if (reconstruct_cmd->parsed()) return run_reconstruct(reconstruct);
        if (demo_cmd->parsed()) return run_haptics_demo(demo);
        if (devices_cmd->parsed()) return run_devices(devices);
        if (soak_cmd->parsed()) return run_soak(soak);
        if (case_cmd->parsed() && case_args.action == "plan") return run_case_plan(plan_args);
        if (case_cmd->parsed()) return run_case(case_args);
        if (exam_cmd->parsed()) return run_exam(exam_args);
        if (records_cmd->parsed())
            return records_export_cmd->parsed() ? run_records_export(records_args)
                   : records_add_cmd->parsed()  ? run_records_add(records_args)
                                                : run_records(records_args);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim %s: error: %s\n", which, e.what());
        return kExitFailure;
    }
    return kExitFailure;
}

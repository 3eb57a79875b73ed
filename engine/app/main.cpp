// echosim: one binary, one subcommand per job (DESIGN.md §4).
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"

namespace {

void add_gpu_options(CLI::App* cmd, echosim::app::GpuArgs& gpu)
{
    cmd->add_option("--gpu", gpu.gpu, "Vulkan device to use: part of its name, or cpu/lavapipe, discrete, integrated (else ECHOSIM_GPU)");
    cmd->add_flag("--validation", gpu.validation, "enable the Khronos validation layer; any message makes the command fail");
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace echosim::app;
    CLI::App app{"echosim: real-time echographic simulator with force feedback"};
    app.require_subcommand(1);

    RenderArgs render;
    auto* render_cmd = app.add_subcommand("render", "render one frame headless to a PNG");
    render_cmd->add_option("--out", render.out, "PNG file to write")->required();
    render_cmd->add_option("--width", render.width, "image width [px]")->check(CLI::Range(16u, 16384u));
    render_cmd->add_option("--height", render.height, "image height [px]")->check(CLI::Range(16u, 16384u));
    render_cmd->add_option("--pose", render.pose, "probe pose x,y,z,qw,qx,qy,qz in world (LPS mm)");
    render_cmd->add_option("--press-mm", render.press_mm, "press the probe this far into the skin and let the tissue settle [mm]")
        ->check(CLI::Range(0.0, 30.0));
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

    BenchArgs bench;
    auto* bench_cmd = app.add_subcommand("bench", "run the benchmarks and print a table");
    bench_cmd->add_option("names", bench.names, "benchmarks to run (default: all)");
    bench_cmd->add_option("--json", bench.json, "also write the results as JSON to this file");
    bench_cmd->add_option("--min-time", bench.min_time_s, "seconds each measurement runs at least")->check(CLI::PositiveNumber);
    add_gpu_options(bench_cmd, bench.gpu);

    CLI11_PARSE(app, argc, argv);

    const char* which = app.get_subcommands().front()->get_name().c_str();
    try {
        if (render_cmd->parsed()) return run_render(render);
        if (run_cmd->parsed()) return run_window(run);
        if (bench_cmd->parsed()) return run_bench(bench);
        if (measure_cmd->parsed()) return run_measure(measure);
        if (fit_cmd->parsed()) return run_fit(fit);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "echosim %s: error: %s\n", which, e.what());
        return kExitFailure;
    }
    return kExitFailure;
}

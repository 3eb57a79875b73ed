// The subcommands of the `echosim` binary (DESIGN.md §4). Each validates its input and returns the
// process exit code: 0 success, 1 runtime failure, 2 bad input, 3 Vulkan validation messages.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tissue/tissue_model.hpp"

namespace echosim::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitValidation = 3;

// Whether `path` can take the command's output: its folder exists and can be written, the path is
// not something other than a regular file (a device node, a FIFO, a folder), which writing would
// replace, and its name fits the file system (NAME_MAX) with room for the temporaries it is written
// through (PATH_MAX; io/partial_file.hpp, write_together). If not,
// says so on stderr, naming the command and the option, so a command can refuse (exit 2) before it
// spends time on work it cannot save.
bool output_path_usable(const char* command, const char* option, const std::filesystem::path& path);

// A file a command reads or writes, and how messages name it: the option that gives it ("--out"),
// or where it comes from ("--out's labels").
struct NamedPath {
    std::string option;
    std::filesystem::path path;  // empty: none
};

// Whether each output names a file of its own: no two outputs the same file, and no output one of
// the inputs, which writing it would replace. Paths are compared by what they name, not by how they
// are spelt (`./x`, `d/../x`, links, hard links). If not, says so on stderr naming both options, so
// the command can refuse (exit 2) before any work.
bool outputs_distinct(const char* command, const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

// --model FILE: the tissue model a session runs (empty: the shipped thigh), read into `tissue`. A
// file that cannot be read, or a model outside the physical ranges (tissue/physical_ranges.hpp), is
// reported on stderr naming the command, the file and the field, and the call returns false.
bool read_model_option(const char* command, const std::filesystem::path& file, std::optional<tissue::SampleParameters>& tissue);

// Writes files that belong together (a volume and its labels, a sweep and its labels' sweep) so
// that they stay a set: `write(i, path)` writes the i-th of `paths` into a private folder beside
// it, and only once every one is complete are they all renamed into place (with any file a writer
// put beside its own, such as a MetaImage's detached data). A failure midway leaves every old file
// as it was and removes the new ones. The private folders (.echosim-writing-PID-SIX,
// io/owned_temp.hpp) that a killed run left are removed by the next write into the same folder.
// Throws what `write` throws, or std::runtime_error naming the file that could not be moved into
// place.
void write_together(const std::vector<std::filesystem::path>& paths,
                    const std::function<void(std::size_t, const std::filesystem::path&)>& write);

struct GpuArgs {
    std::string gpu;          // --gpu NAME, else ECHOSIM_GPU
    bool validation = false;  // --validation, else ECHOSIM_VALIDATION or a debug build
};

struct RenderArgs {
    GpuArgs gpu;
    std::filesystem::path out;
    std::uint32_t width = 1920;
    std::uint32_t height = 1080;
    std::string pose;  // empty: the probe rests on the patch centre
    double press_mm = -1;  // < 0: no physics, the patch at rest
    std::string camera;    // yaw,pitch,distance[,x,y,z]; empty: the default view
    std::filesystem::path model;  // tissue model JSON (`echosim fit` writes one); empty: the shipped thigh
};
int run_render(const RenderArgs& args);

struct RunArgs {
    GpuArgs gpu;
    int width = 1600;
    int height = 900;
    bool fullscreen = false;
    int frames = 0;         // stop after this many presented frames (0: until the window closes)
    bool exercise = false;  // resize, minimise and toggle fullscreen along the way (smoke tests)
    std::filesystem::path volume;  // empty: the case's default volume (made once, cached)
    std::filesystem::path labels;  // with --volume: its tissue labels (empty: linear deformation)
    std::string case_name = "healthy";
    std::string imaging;  // interpolative or generative; empty: as the case says
    std::filesystem::path model;  // tissue model JSON (`echosim fit` writes one); empty: the shipped thigh
    std::string device = "mouse";      // mouse, spacemouse, openhaptics, simulated-arm or null
    std::filesystem::path trajectory;  // a scripted trajectory CSV instead of a device
    // --igtl [PORT]: serve the live image and probe over OpenIGTLink on this port, as written
    // (validated by run_window: 1..65535); empty: no link
    std::string igtl_port;
    // --igtl-bind ADDRESS: where the link listens (an IPv4 or IPv6 literal, validated by
    // run_window); empty: the loopback interface, this machine alone (igtl/server.hpp)
    std::string igtl_bind;
    // the trainer (app/trainer_window.hpp): --case is a shipped case's id (or random); the kiosk,
    // its idle timeout [s], the trainee records (empty: the user's default), coarse case volumes
    bool kiosk = false;
    double idle_timeout_s = 120;
    std::filesystem::path records;
    bool coarse = false;
};
int run_window(const RunArgs& args);
std::string run_keys_help();  // every key of `echosim run`, for its --help (app/trainer_window.cpp)

struct MeasureArgs {
    std::filesystem::path out;
    std::uint64_t seed = 1;
};
int run_measure(const MeasureArgs& args);

struct FitArgs {
    std::filesystem::path data;
    std::filesystem::path out;
    std::filesystem::path report;  // empty: no report folder
    std::string method = "lm";     // lm | steepest
    bool json = false;
};
int run_fit(const FitArgs& args);

struct PhantomArgs {
    std::string case_name = "healthy";
    std::filesystem::path out;
    std::filesystem::path labels;  // the phantom's label map (NRRD); empty: none
    int frames = 240;
    double pixel_mm = 0.1;
    std::uint64_t seed = 1;
    bool compressed = false;
    bool cpu = false;  // synthesise on the CPU twin, not the GPU
    GpuArgs gpu;
};
int run_phantom(const PhantomArgs& args);

// Options left empty take the PLUS configuration's value (with --config), else echosim's default.
struct ReconstructArgs {
    std::filesystem::path sweep;
    std::filesystem::path out;                // .nrrd or .mha
    std::filesystem::path config;             // PLUS device-set configuration (empty: none)
    std::string image_to_reference;           // the frame to reconstruct in, or FromToTo (empty: Reference)
    std::optional<double> voxel_mm;           // default 0.3, or the configuration's OutputSpacing
    std::optional<std::string> splat;         // nearest | trilinear
    std::optional<std::string> compound;      // mean | max | latest
    std::optional<std::string> fill_holes;    // on | off
    std::optional<std::string> grid;          // plus | sweep (default: plus with --config, else sweep)
    std::optional<std::uint64_t> budget_mb;   // [MiB] default 4096; refused past 64 bits of bytes or the machine's memory
    bool gzip = false;
};
int run_reconstruct(const ReconstructArgs& args);

struct SliceArgs {
    GpuArgs gpu;
    std::filesystem::path volume;  // empty: the case's default volume (cached)
    std::filesystem::path labels;  // empty: none (the paper's linear deformation)
    std::filesystem::path out;     // .png or .nrrd
    std::string pose;              // the probe resting on the skin; empty: the patch centre
    double press_mm = -1;          // < 0: not pressed (unless --force)
    double force_n = -1;           // < 0: not asked
    bool cpu = false;
    std::string imaging = "interpolative";  // echo::Imaging's name
    std::filesystem::path model;  // tissue model JSON (`echosim fit` writes one); empty: the shipped thigh
    std::string case_name = "healthy";
    bool coarse = false;  // the default volume at 0.6 mm (echo::coarse_case_volume_options)
    double width_mm = 40, depth_mm = 50, pixel_mm = 0.1;
    double gain_db = 0, dynamic_range_db = 55;
    double venous_mmhg = 10, heart_rate_bpm = 70, time_s = 0;
};
int run_slice(const SliceArgs& args);

struct HapticsDemoArgs {
    std::filesystem::path out;
    double physics_hz = 100.0;
    bool json = false;
};
int run_haptics_demo(const HapticsDemoArgs& args);

struct BenchArgs {
    GpuArgs gpu;
    std::vector<std::string> names;  // empty: all
    std::filesystem::path json;
    double min_time_s = 1.0;
    std::string filter = ".";  // Google Benchmark's filter over the row names
    int repetitions = 1;       // runs of each row; more than one: its median, with the spread (bench/harness.hpp)
};
int run_bench(const BenchArgs& args);

struct SoakArgs {
    GpuArgs gpu;
    double seconds = 120;
    std::filesystem::path json;  // empty: no report file
    std::uint32_t width = 1280, height = 720;
    std::string deadlines = "strict";  // strict | p99 | report (app/soak.hpp)
};
int run_soak(const SoakArgs& args);

struct DevicesArgs {
    bool json = false;  // a JSON array instead of the text
};
int run_devices(const DevicesArgs& args);

// `echosim case validate F...` (each file read as the exam reads it: "F: ok (id, N stations,
// protocol)", or the error naming the file and the field; exit 2 when any is bad) and `echosim case
// list` (the shipped cases: id and title).
struct CaseArgs {
    std::string action;                       // "validate" or "list"
    std::vector<std::filesystem::path> files;  // validate: the case files
};
int run_case(const CaseArgs& args);

// `echosim case plan` (app/cmd_case_plan.cpp): a case's scripted exams.
struct CasePlanArgs {
    std::filesystem::path scenario;  // a case file; empty: --case
    std::string case_id;             // a shipped case (empty: healthy)
    std::string style = "correct";   // correct or an error (exam::plan_error_name)
    int at = -1;                     // the station the error happens at (-1: one that fits it)
    std::filesystem::path out;       // the script
    std::filesystem::path all;       // every shipped case's correct exam and errors, into this folder
};
int run_case_plan(const CasePlanArgs& args);

// `echosim exam` (app/cmd_exam.cpp): a scripted exam, headless and repeatable to the byte.
struct ExamArgs {
    GpuArgs gpu;
    std::filesystem::path scenario;    // a case file; empty: --case
    std::string case_id;               // a shipped case's id, or "random" (empty: healthy)
    std::uint64_t seed = 1;            // --case random's draw
    std::filesystem::path trajectory;  // the exam's script; empty: the case's shipped correct exam
    std::filesystem::path out;         // the report's folder
    double frames_per_s = 10;          // frames written per simulated second (0: images at the stations only)
    std::string trainee = "scripted";
    std::filesystem::path records;     // empty: the user's default database
    bool no_records = false;
    bool coarse = false;               // the case's volume at 0.6 mm (seconds to make): tests and benchmarks
    std::string imaging;               // interpolative or generative; empty: as the scenario says
};
int run_exam(const ExamArgs& args);

}  // namespace echosim::app

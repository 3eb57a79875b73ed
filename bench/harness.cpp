#include "bench/harness.hpp"

#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/gpu_args.hpp"
#include "bench/goals.hpp"
#include "bench/suites.hpp"
#include "io/partial_file.hpp"

namespace echosim::bench {

const std::vector<Suite>& suites()
{
    static const std::vector<Suite> all = {
        {"render", "headless frame of the default scene (offscreen, Vulkan)", register_render, true},
        {"fit", "two-step tissue fit on assets/measurements/thigh.csv", register_fit, false},
        {"physics", "tissue dynamics steps with the probe pressing and sliding (one core; and all, from 2500 nodes)", register_physics, false},
        {"reconstruct", "freehand reconstruction of 300 tracked 640x480 frames", register_reconstruct, false},
        {"slice", "echographic image (deform, slice, post) of a pressed frame, 0.3 and 0.1 mm volumes, frames/s", register_slice, true},
        {"haptics", "the 1 kHz haptic loop's period error over 30 s with the physics and headless rendering running; one force computation",
         register_haptics, true},
        {"arm", "the force path in real time through the simulated arm (its servo, the haptic loop, the physics) over 10 s", register_arm, false},
        {"exam", "the shipped extended exam of the healthy case headless in lock-step: frames at 10 per simulated second, and images at "
                 "the stations only, against real time", register_exam, true},
        {"bmode", "B-mode synthesis of sweep frames (scatterers, beam, PSF, log compression) at 400x500, 512x512, 1024x1024, frames/s",
         register_bmode, true},
        {"e2e", "from a probe move to the presented echographic image showing it, real time: frames and milliseconds, headless and in a "
                "window when there is a display", register_e2e, true},
        {"ui", "the trainer's UI pass in a 1920x1080 offscreen frame on its start, exam and report screens: the frame with it and "
               "without, ms and the UI's share (issue 32: at most 10 %)", register_ui, true},
    };
    return all;
}

namespace {

std::string cpu_model()
{
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown";
}

nlohmann::json machine(const std::string& gpu)
{
    utsname u{};
    uname(&u);
    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    return {{"cpu", cpu_model()},
            {"cores", std::thread::hardware_concurrency()},
            {"os", std::string(u.sysname) + " " + u.release},
            {"gpu", gpu},
            {"date", date}};
}

// One line of the table as the rows come in: name, time per iteration, iterations, then the
// row's other fields.
void print_row(const nlohmann::json& row)
{
    std::printf("  %-34s %10.3f ms %8lld it", row["name"].get<std::string>().c_str(), row["ms_per_iteration"].get<double>(),
                static_cast<long long>(row["iterations"].get<double>()));
    for (const auto& [key, value] : row.items()) {
        if (key == "name" || key == "ms_per_iteration" || key == "iterations") continue;
        if (value.is_number())
            std::printf("  %s=%g", key.c_str(), value.get<double>());
        else if (value.is_string())
            std::printf("  %s=%s", key.c_str(), value.get<std::string>().c_str());
    }
    std::printf("\n");
    std::fflush(stdout);
}

// Collects Google Benchmark's runs instead of printing them; a row run several times
// (--repetitions) becomes one row, its median (median_row), when its last repetition is in.
class Collector : public benchmark::BenchmarkReporter {
public:
    bool ReportContext(const Context&) override { return true; }
    void ReportRuns(const std::vector<Run>& runs) override
    {
        for (const Run& run : runs) {
            if (run.error_occurred) {
                errors.push_back(run.benchmark_name() + ": " + run.error_message);
                continue;
            }
            if (run.run_type == Run::RT_Aggregate) continue;  // Google Benchmark's mean, median, stddev: ours has the spread too
            nlohmann::json row;
            row["name"] = run.run_name.function_name;
            // GetAdjustedRealTime is in the run's own time unit
            row["ms_per_iteration"] = run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
            row["iterations"] = run.iterations;
            std::vector<std::string> rates;
            for (const auto& [key, counter] : run.counters) {
                row[key] = counter.value;
                if ((counter.flags & benchmark::Counter::kIsRate) != 0) rates.push_back(key);
            }
            // text fields: a suite labels its rows "key=value key=value"
            std::istringstream label(run.report_label);
            for (std::string field; label >> field;)
                if (const auto eq = field.find('='); eq != std::string::npos) row[field.substr(0, eq)] = field.substr(eq + 1);
            if (run.repetitions <= 1) {
                add(row);
                continue;
            }
            std::vector<nlohmann::json>& so_far = repeated_[run.run_name.function_name];
            so_far.push_back(row);
            if (std::int64_t(so_far.size()) == run.repetitions) {
                add(median_row(so_far, rates));
                so_far.clear();
            }
        }
    }
    std::vector<nlohmann::json> rows;
    std::vector<std::string> errors;

private:
    void add(const nlohmann::json& row)
    {
        rows.push_back(row);
        print_row(row);
    }
    std::map<std::string, std::vector<nlohmann::json>> repeated_;  // by row name: the repetitions in so far
};

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

nlohmann::json median_row(const std::vector<nlohmann::json>& repetitions, const std::vector<std::string>& rates)
{
    if (repetitions.empty()) throw std::invalid_argument("median_row: no repetitions");
    nlohmann::json out = repetitions.front();
    for (const auto& [key, value] : repetitions.front().items()) {
        if (!value.is_number()) continue;
        std::vector<double> values;
        for (const nlohmann::json& r : repetitions)
            if (r.contains(key) && r[key].is_number()) values.push_back(r[key].get<double>());
        out[key] = median(values);
        if (std::find(rates.begin(), rates.end(), key) != rates.end()) {
            out[key + "_min"] = *std::min_element(values.begin(), values.end());
            out[key + "_max"] = *std::max_element(values.begin(), values.end());
        }
    }
    out["repetitions"] = repetitions.size();
    return out;
}

}  // namespace echosim::bench

namespace echosim::app {

int run_bench(const BenchArgs& args)
{
    using namespace echosim::bench;
    if (!args.json.empty() && !output_path_usable("bench", "--json", args.json)) return kExitBadInput;
    std::vector<const Suite*> chosen;
    for (const Suite& s : suites())
        if (args.names.empty() || std::find(args.names.begin(), args.names.end(), s.name) != args.names.end())
            chosen.push_back(&s);
    for (const std::string& n : args.names)
        if (std::none_of(suites().begin(), suites().end(), [&](const Suite& s) { return s.name == n; })) {
            std::string known;
            for (const Suite& s : suites()) known += " " + s.name;
            std::fprintf(stderr, "echosim bench: unknown benchmark '%s'; known:%s\n", n.c_str(), known.c_str());
            return kExitBadInput;
        }

    if (args.repetitions < 1) {
        std::fprintf(stderr, "echosim bench: --repetitions %d: at least 1\n", args.repetitions);
        return kExitBadInput;
    }
    // Google Benchmark takes the repetitions every row runs as a flag of its own
    const std::string repetitions_flag = "--benchmark_repetitions=" + std::to_string(args.repetitions);
    std::vector<char*> flags = {const_cast<char*>("echosim"), const_cast<char*>(repetitions_flag.c_str())};
    int flag_count = int(flags.size());
    benchmark::Initialize(&flag_count, flags.data());
    SuiteOptions options{context_options(args.gpu), args.min_time_s};
    nlohmann::json report = nlohmann::json::array();
    int status = kExitOk;
    std::size_t ran = 0;
    for (const Suite* suite : chosen) {
        std::string gpu_name = "none";
        if (suite->uses_gpu) {
            gpu::Context probe(options.gpu);
            gpu_name = probe.device_name();
        }
        std::printf("%s: %s%s%s\n", suite->name.c_str(), suite->what.c_str(), suite->uses_gpu ? " on " : "",
                    suite->uses_gpu ? gpu_name.c_str() : "");
        benchmark::ClearRegisteredBenchmarks();
        std::shared_ptr<void> keep = suite->register_benchmarks(options);
        Collector collector;
        ran += benchmark::RunSpecifiedBenchmarks(&collector, args.filter);
        keep.reset();
        for (const auto& e : collector.errors) {
            std::fprintf(stderr, "echosim bench: %s\n", e.c_str());
            status = kExitFailure;
        }
        report.push_back({{"bench", suite->name}, {"machine", machine(gpu_name)}, {"results", collector.rows}});
    }
    if (ran == 0) {
        std::fprintf(stderr, "echosim bench: no benchmark row matches --filter '%s'\n", args.filter.c_str());
        return kExitBadInput;
    }
    // the goals of DESIGN.md §5 that these suites measure, one table
    const std::vector<GoalLine> goals = evaluate_goals(design_goals(), report);
    if (!goals.empty()) std::printf("\nagainst the goals (DESIGN.md §5):\n%s", goal_table(goals).c_str());
    for (nlohmann::json& suite : report) suite["goals"] = goal_lines_json(goals, suite["bench"].get<std::string>());
    if (!args.json.empty()) {
        // one suite: its object as DESIGN.md shows it; several: an array of them
        io::write_file<std::runtime_error>(args.json, (report.size() == 1 ? report[0] : report).dump(2) + "\n");
    }
    return status;
}

}  // namespace echosim::app

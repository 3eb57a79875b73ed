#include "bench/harness.hpp"

#include <sys/utsname.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
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

// Collects Google Benchmark's runs instead of printing them.
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
            nlohmann::json row;
            row["name"] = run.run_name.function_name;
            // GetAdjustedRealTime is in the run's own time unit
            row["ms_per_iteration"] = run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
            row["iterations"] = run.iterations;
            for (const auto& [key, counter] : run.counters) row[key] = counter.value;
            // text fields: a suite labels its rows "key=value key=value"
            std::istringstream label(run.report_label);
            for (std::string field; label >> field;)
                if (const auto eq = field.find('='); eq != std::string::npos) row[field.substr(0, eq)] = field.substr(eq + 1);
            rows.push_back(row);
            std::printf("  %-34s %10.3f ms %8lld it", run.run_name.function_name.c_str(), double(row["ms_per_iteration"]),
                        static_cast<long long>(run.iterations));
            for (const auto& [key, counter] : run.counters) std::printf("  %s=%g", key.c_str(), counter.value);
            if (!run.report_label.empty()) std::printf("  %s", run.report_label.c_str());
            std::printf("\n");
            std::fflush(stdout);
        }
    }
    std::vector<nlohmann::json> rows;
    std::vector<std::string> errors;
};

}  // namespace
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

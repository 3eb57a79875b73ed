// The benchmark harness behind `echosim bench`: Google Benchmark measures (warm-up, iteration count,
// real time), and this harness turns its runs into DESIGN.md's table and JSON
// ({"bench": NAME, "machine": {...}, "results": [...]}). Each suite registers its benchmarks and
// reports its figures as Google Benchmark counters, which become the JSON row's fields. After every
// suite ran, the goals those suites measure (bench/goals.hpp) make one table, and each suite's JSON
// object gets its lines ("goals").
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu/context.hpp"

namespace echosim::bench {

struct SuiteOptions {
    gpu::ContextOptions gpu;
    double min_time_s = 1.0;
};

// One row from a row's repetitions (`echosim bench --repetitions N`): every numeric field the
// median of its values, and each field named in `rates` also with its least and greatest
// (`fps_min`, `fps_max`), so a shared machine's spread is on record beside the figure judged.
// Text fields come from the first repetition; `repetitions` says how many there were. Throws
// std::invalid_argument on no rows.
nlohmann::json median_row(const std::vector<nlohmann::json>& repetitions, const std::vector<std::string>& rates);

struct Suite {
    std::string name;
    std::string what;  // one line for the table header
    // Registers the suite's benchmarks; what it returns (contexts, scenes) lives until they ran.
    std::function<std::shared_ptr<void>(const SuiteOptions&)> register_benchmarks;
    bool uses_gpu = false;
};

const std::vector<Suite>& suites();

}  // namespace echosim::bench

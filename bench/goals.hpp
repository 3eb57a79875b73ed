// DESIGN.md §5 ("Numbers we aim for") as data: each goal names the suite, the row and the field
// that measure it, how the figure compares with the goal, and how to show it. After every suite
// ran, `echosim bench` reads the goals of the suites it ran from their results and prints one
// table (what | the paper (2005) | our goal | measured | met?); each suite's JSON object carries its
// lines ("goals"). A goal whose row did not run (filtered out, or a real GPU's row on a machine with
// none) is "not measured", with the reason. bench/RESULTS.md keeps the table current.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace echosim::bench {

enum class Compare { at_least, at_most };

struct Goal {
    std::string what;   // the line's name, e.g. "physics rate, 2,500 nodes, one core"
    std::string paper;  // what the paper reports for it ("-" where it reports nothing)
    std::string goal;   // DESIGN.md §5's words
    // where the figure is: the suite, the row's name, the row's field
    std::string suite, row, field;
    Compare compare = Compare::at_least;
    double threshold = 0;  // in the field's own units
    // shown as field * scale, in `unit`
    double scale = 1;
    std::string unit;
    std::string missing = "row not run";  // why, when the suite ran but the row is not there
    // a goal of lavapipe's (of the 2-core machine): a row that says it ran on another device (its
    // counter cpu_device 0, a real GPU's figure) does not measure it
    bool lavapipe_only = false;
};

// DESIGN.md §5's goals that the suites measure, in its order.
const std::vector<Goal>& design_goals();

enum class GoalStatus { met, not_met, not_measured };
const char* to_string(GoalStatus status);  // "yes", "no", "not measured"

struct GoalLine {
    const Goal* goal = nullptr;
    GoalStatus status = GoalStatus::not_measured;
    double value = 0;       // the field as read (when measured)
    std::string measured;   // as shown: "2731 steps/s", or "not measured (no GPU)"
};

// The lines of the goals whose suite is in `report`: the suites' results as `echosim bench` writes
// them, an array of {"bench": NAME, "machine": {...}, "results": [{"name": ROW, FIELD: ...}, ...]}.
std::vector<GoalLine> evaluate_goals(std::span<const Goal> goals, const nlohmann::json& report);

// The lines as a Markdown table (what | the paper (2005) | our goal | measured | met?).
std::string goal_table(std::span<const GoalLine> lines);
// The lines of one suite as JSON: [{"what", "paper", "goal", "row", "field", "threshold",
// "value" (null when not measured), "measured", "met": "yes" | "no" | "not measured"}, ...].
nlohmann::json goal_lines_json(std::span<const GoalLine> lines, const std::string& suite);

}  // namespace echosim::bench

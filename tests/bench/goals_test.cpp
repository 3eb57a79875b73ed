// The goal table of `echosim bench` (bench/goals.cpp) on made-up suite results: a goal met, one not
// met, one whose row did not run, one whose suite did not run; a row's repetitions as their median;
// and the shipped goals name rows the suites write.
#include "bench/goals.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bench/harness.hpp"

namespace echosim::bench {
namespace {

const std::vector<Goal> kGoals = {
    {"rate", "100 Hz", ">= 1 kHz", "physics", "physics/2500", "steps_per_s", Compare::at_least, 1000, 1, "steps/s"},
    {"error", "5 %", "<= 5 %", "fit", "fit/lm", "rel_error", Compare::at_most, 0.05, 100, "%"},
    {"time", "-", "< 5 s", "fit", "fit/lm", "ms_per_iteration", Compare::at_most, 5000, 0.001, "s"},
    {"gpu", "-", ">= 1000 fps", "physics", "physics/gpu", "fps", Compare::at_least, 1000, 1, "fps", "no GPU"},
    {"unrun suite", "-", "-", "slice", "slice/x", "fps", Compare::at_least, 1, 1, "fps"},
};

nlohmann::json report()
{
    return nlohmann::json::array({
        {{"bench", "physics"}, {"machine", {{"gpu", "none"}}}, {"results", {{{"name", "physics/2500"}, {"steps_per_s", 2731.4}}}}},
        {{"bench", "fit"},
         {"machine", {{"gpu", "none"}}},
         {"results", {{{"name", "fit/lm"}, {"rel_error", 0.0463}, {"ms_per_iteration", 6100.0}}}}},
    });
}

TEST(BenchGoals, MetNotMetAndNotMeasured)
{
    const std::vector<GoalLine> lines = evaluate_goals(kGoals, report());
    ASSERT_EQ(lines.size(), 4u);  // the slice suite did not run: no line
    EXPECT_EQ(lines[0].status, GoalStatus::met);
    EXPECT_EQ(lines[0].measured, "2731 steps/s");
    EXPECT_EQ(lines[1].status, GoalStatus::met);  // 4.63 % <= 5 %
    EXPECT_EQ(lines[1].measured, "4.63 %");
    EXPECT_EQ(lines[2].status, GoalStatus::not_met);  // 6.1 s
    EXPECT_EQ(lines[2].measured, "6.1 s");
    EXPECT_EQ(lines[3].status, GoalStatus::not_measured);
    EXPECT_EQ(lines[3].measured, "not measured (no GPU)");
}

// A goal of lavapipe's is not measured by a row that ran on a real GPU (its cpu_device counter 0),
// is by one that ran on lavapipe (1), and by a row that does not say (results recorded before).
TEST(BenchGoals, ALavapipeGoalIsNotMeasuredByAGpusRow)
{
    std::vector<Goal> goals = {kGoals[0]};
    goals[0].lavapipe_only = true;
    nlohmann::json r = report();
    EXPECT_EQ(evaluate_goals(goals, r)[0].status, GoalStatus::met);
    r[0]["results"][0]["cpu_device"] = 1;
    EXPECT_EQ(evaluate_goals(goals, r)[0].status, GoalStatus::met);
    r[0]["results"][0]["cpu_device"] = 0;
    const GoalLine line = evaluate_goals(goals, r)[0];
    EXPECT_EQ(line.status, GoalStatus::not_measured);
    EXPECT_EQ(line.measured, "not measured (ran on a GPU, not lavapipe)");
    goals[0].lavapipe_only = false;  // a goal of any device's reads it
    EXPECT_EQ(evaluate_goals(goals, r)[0].status, GoalStatus::met);
}

TEST(BenchGoals, TheBoundaryCountsAsMet)
{
    nlohmann::json r = report();
    r[0]["results"][0]["steps_per_s"] = 1000.0;
    r[1]["results"][0]["ms_per_iteration"] = 5000.0;
    const std::vector<GoalLine> lines = evaluate_goals(kGoals, r);
    EXPECT_EQ(lines[0].status, GoalStatus::met);
    EXPECT_EQ(lines[2].status, GoalStatus::met);
}

TEST(BenchGoals, TableAndJson)
{
    const std::vector<GoalLine> lines = evaluate_goals(kGoals, report());
    const std::string table = goal_table(lines);
    EXPECT_NE(table.find("| what | the paper (2005) | our goal | measured | met? |"), std::string::npos) << table;
    EXPECT_NE(table.find("| rate | 100 Hz | >= 1 kHz | 2731 steps/s | yes |"), std::string::npos) << table;
    EXPECT_NE(table.find("| time | - | < 5 s | 6.1 s | no |"), std::string::npos) << table;
    EXPECT_NE(table.find("| gpu | - | >= 1000 fps | not measured (no GPU) | not measured |"), std::string::npos) << table;

    const nlohmann::json physics = goal_lines_json(lines, "physics");
    ASSERT_EQ(physics.size(), 2u);
    EXPECT_EQ(physics[0]["met"], "yes");
    EXPECT_EQ(physics[0]["value"], 2731.4);
    EXPECT_EQ(physics[0]["compare"], ">=");
    EXPECT_TRUE(physics[1]["value"].is_null());
    EXPECT_EQ(goal_lines_json(lines, "fit").size(), 2u);
}

TEST(BenchGoals, ARepeatedRowIsItsMedianWithItsSpread)
{
    // five runs of one row on a noisy machine: the median is judged, the spread is said
    std::vector<nlohmann::json> runs;
    for (double fps : {240.0, 131.0, 262.0, 255.0, 199.0})
        runs.push_back({{"name", "physics/2500"}, {"steps_per_s", fps}, {"ms_per_iteration", 1000.0 / fps}, {"width", 1024.0}, {"backend", "lavapipe"}});
    const nlohmann::json row = median_row(runs, {"steps_per_s"});
    EXPECT_EQ(row["steps_per_s"], 240.0);
    EXPECT_EQ(row["steps_per_s_min"], 131.0);
    EXPECT_EQ(row["steps_per_s_max"], 262.0);
    EXPECT_DOUBLE_EQ(row["ms_per_iteration"].get<double>(), 1000.0 / 240.0);
    EXPECT_EQ(row["width"], 1024.0);
    EXPECT_EQ(row["backend"], "lavapipe");
    EXPECT_EQ(row["repetitions"], 5);
    EXPECT_FALSE(row.contains("width_min")) << "only the rates get a spread";
    // an even count: the mean of the middle two
    runs.pop_back();
    EXPECT_EQ(median_row(runs, {})["steps_per_s"], 247.5);
    EXPECT_THROW(median_row({}, {}), std::invalid_argument);

    nlohmann::json r = report();
    r[0]["results"][0] = median_row(std::vector<nlohmann::json>(runs.begin(), runs.end()), {"steps_per_s"});
    const std::vector<GoalLine> lines = evaluate_goals(kGoals, r);
    EXPECT_EQ(lines[0].measured, "248 steps/s (median of 4: 131-262)");
    EXPECT_EQ(lines[0].status, GoalStatus::not_met);
}

// The shipped goals against the recorded results (bench/results/*.json, the suites' own JSON): the
// 2-core machine's, then a lent H200's (bench/device/gpu_checks.sh), whose rows the real GPU's goals
// read (the 2-core machine's come first: its rows are the lavapipe goals'). Every goal finds its row
// and field.
TEST(BenchGoals, ShippedGoalsReadTheRecordedResults)
{
    nlohmann::json recorded = nlohmann::json::array();
    for (const char* file : {"fit_2core.json", "physics_2core.json", "haptics_2core_floor.json", "slice_2core.json", "reconstruct_2core.json",
                             "exam_2core.json", "e2e_2core.json", "ui_2core.json", "bmode_live_2core.json", "slice_h200.json",
                             "bmode_h200.json"}) {
        std::ifstream in(std::filesystem::path(ECHOSIM_BENCH_RESULTS_DIR) / file);
        ASSERT_TRUE(in) << file;
        recorded.push_back(nlohmann::json::parse(in));
    }
    const std::vector<GoalLine> lines = evaluate_goals(design_goals(), recorded);
    EXPECT_EQ(lines.size(), design_goals().size());
    for (const GoalLine& l : lines) EXPECT_NE(l.status, GoalStatus::not_measured) << l.goal->what << ": " << l.measured;
}

}  // namespace
}  // namespace echosim::bench

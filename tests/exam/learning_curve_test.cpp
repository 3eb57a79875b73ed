// The learning curve from the records: scores in order and the CUSUM per station type against
// values worked out by hand from Bolsin and Colson's formulas (p0 0.10, p1 0.20, alpha = beta = 0.10).
#include <filesystem>

#include <gtest/gtest.h>

#include "exam/learning_curve.hpp"
#include "report_fixture.hpp"
#include "test_files.hpp"

namespace echosim::exam {
namespace {

// s = ln(0.9/0.8) / ln(0.2*0.9 / (0.1*0.8)) = 0.117783 / 0.810930; h = ln(0.9/0.1) / 0.810930
constexpr double kS = 0.1452443543242726;
constexpr double kH = 2.709511291351455;

TEST(LearningCurve, LimitsFromTheFormulas)
{
    const CusumLimits l = cusum_limits({});
    EXPECT_NEAR(l.s, kS, 1e-12);
    EXPECT_NEAR(l.h0, kH, 1e-12);
    EXPECT_NEAR(l.h1, kH, 1e-12);
    EXPECT_THROW(cusum_limits({0.2, 0.1, 0.1, 0.1}), std::invalid_argument);
    EXPECT_THROW(cusum_limits({0.1, 0.2, 0.0, 0.1}), std::invalid_argument);
    // 19 successes in a row reach -h0; 18 do not
    std::vector<bool> run(18, true);
    EXPECT_EQ(cusum_verdict(cusum_path(run, l), l), CusumVerdict::undecided);
    run.push_back(true);
    EXPECT_EQ(cusum_verdict(cusum_path(run, l), l), CusumVerdict::acceptable);
    // 4 failures in a row: 4 (1 - s) = 3.42 >= h1
    EXPECT_EQ(cusum_verdict(cusum_path({false, false, false, false}, l), l), CusumVerdict::unacceptable);
    EXPECT_EQ(cusum_verdict(cusum_path({false, false, false}, l), l), CusumVerdict::undecided);
}

TEST(LearningCurve, ThreeExamsAgainstAHandComputedCusum)
{
    const auto dir = echosim::test::temp_path("curve", "db");
    std::filesystem::remove_all(dir);
    Records records(dir / "records.sqlite");
    // make_report(): CFV success, SFJ failure (too little pressure, wrong call), FV 2 cm failure
    // (skipped), FV 6 cm success
    ExamReport first = test::make_report();
    ExamReport second = test::make_report();
    second.score = 0.75;
    second.errors.erase(second.errors.begin());  // the SFJ adequately pressed, but still called wrong
    second.stations[2].reached = true;           // FV 2 cm reached and called right
    second.stations[2].call = Call::compressible;
    second.stations[2].call_correct = true;
    second.errors.pop_back();
    ExamReport third = test::make_report();
    third.score = 1.0;
    third.passed = true;
    third.errors.clear();
    for (StationResult& s : third.stations) s.reached = true, s.call_correct = true;
    third.stations[0].call_correct = false;  // CFV called wrong this time
    ExamReport other = test::make_report();
    other.trainee = "Someone Else";
    records.store(first);
    records.store(other);
    records.store(second);
    records.store(third);

    const LearningCurve c = learning_curve(records, "Ada Lovelace");
    ASSERT_EQ(c.sessions.size(), 3u);
    EXPECT_EQ(c.sessions[0].session_id, 1);
    EXPECT_EQ(c.sessions[1].session_id, 3);
    EXPECT_EQ(c.sessions[2].session_id, 4);
    EXPECT_DOUBLE_EQ(c.sessions[1].score, 0.75);
    EXPECT_TRUE(c.sessions[2].passed);

    // types in the order met: cfv, sfj, fv (two stations a session), and nothing else
    ASSERT_EQ(c.stations.size(), 3u);
    EXPECT_EQ(c.stations[0].type, "cfv");
    EXPECT_EQ(c.stations[1].type, "sfj");
    EXPECT_EQ(c.stations[2].type, "fv");
    // cfv: success, success, failure
    EXPECT_EQ(c.stations[0].successes, (std::vector<bool>{true, true, false}));
    ASSERT_EQ(c.stations[0].cusum.size(), 3u);
    EXPECT_NEAR(c.stations[0].cusum[0], -kS, 1e-12);
    EXPECT_NEAR(c.stations[0].cusum[1], -2 * kS, 1e-12);
    EXPECT_NEAR(c.stations[0].cusum[2], 0.7095112913514547 - kS, 1e-12);  // 1 - 3s = 0.56427
    // sfj: failure, failure (wrong call), success
    EXPECT_EQ(c.stations[1].successes, (std::vector<bool>{false, false, true}));
    EXPECT_NEAR(c.stations[1].cusum[1], 1.7095112913514547, 1e-12);  // 2 (1 - s)
    EXPECT_NEAR(c.stations[1].cusum[2], 1.5642669370271822, 1e-12);  // 2 - 3s
    // fv: [FV 2 cm failure, FV 6 cm success] [success, success] [success, success]
    EXPECT_EQ(c.stations[2].successes, (std::vector<bool>{false, true, true, true, true, true}));
    EXPECT_NEAR(c.stations[2].cusum.back(), 1 - 6 * kS, 1e-12);  // 0.12853
    for (const StationTypeCurve& t : c.stations) EXPECT_EQ(t.verdict, CusumVerdict::undecided);

    const std::string table = learning_curve_table(c);
    EXPECT_NE(table.find("Trainee Ada Lovelace: 3 sessions"), std::string::npos) << table;
    EXPECT_NE(table.find("s 0.145, h0 2.71, h1 2.71"), std::string::npos) << table;
    EXPECT_NE(table.find("  sfj                  3         2    1.56  undecided"), std::string::npos) << table;
    const io::RgbaImage plot = learning_curve_plot({c});
    EXPECT_EQ(plot.width, 1800u);
    EXPECT_EQ(plot.height, 600u);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace echosim::exam

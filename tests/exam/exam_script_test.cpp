#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "exam/exam_script.hpp"

namespace echosim::exam {
namespace {

StationTruth station(const char* name, float z, bool thrombosed = false)
{
    StationTruth t;
    t.name = name;
    t.vein = {glm::dvec3(0, 25, z), glm::dvec3(0, 0, 1), 4.0};
    t.artery = {glm::dvec3(15, 25, z), glm::dvec3(0, 0, 1), 3.5};
    t.thrombosed = thrombosed;
    t.ideal_probe.position = glm::vec3(0, 0, z);  // identity orientation: beam along +y
    return t;
}

TEST(ExamScript, SplitsTheCallsFromThePoses)
{
    const std::string text =
        "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz,call\n"
        "0,1,2,3,1,0,0,0,\n"
        "# a comment\n"
        "0.5,1,2,4,1,0,0,0,not-compressible\n"
        "1,1,2,5,1,0,0,0,compressible\n";
    const SplitScript s = split_exam_script(text, "x.csv");
    EXPECT_EQ(s.trajectory_csv,
              "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n0,1,2,3,1,0,0,0\n# a comment\n0.5,1,2,4,1,0,0,0\n1,1,2,5,1,0,0,0\n");
    ASSERT_EQ(s.calls.size(), 2u);
    EXPECT_EQ(s.calls[0].call, Call::not_compressible);
    EXPECT_DOUBLE_EQ(s.calls[0].t_s, 0.5);
    EXPECT_EQ(s.calls[1].call, Call::compressible);
}

TEST(ExamScript, APlainTrajectoryPassesUnchanged)
{
    const std::string text = "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n0,1,2,3,1,0,0,0\n";
    const SplitScript s = split_exam_script(text, "x.csv");
    EXPECT_EQ(s.trajectory_csv, text);
    EXPECT_TRUE(s.calls.empty());
}

TEST(ExamScript, AnUnknownCallIsRefusedNamingTheLine)
{
    try {
        split_exam_script("t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz,call\n0,1,2,3,1,0,0,0,clot\n", "exam.csv");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("exam.csv:2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'clot'"), std::string::npos) << e.what();
    }
}

TEST(ExamScript, PlannedExamPressesEachStationAndCallsTheTruth)
{
    const std::vector<StationTruth> stations{station("A", -100), station("B", -120, true)};
    const ExamScript plan = plan_exam(stations, {10.0, 12.0});
    // per station: lifted, on the skin, pressed, held, released, lifted (the first starts lifted)
    ASSERT_EQ(plan.poses.size(), 12u);
    EXPECT_NEAR(plan.poses[2].pose.position.y, 10.0f, 1e-5f);  // pressed 10 mm along +y
    EXPECT_NEAR(plan.poses[8].pose.position.y, 12.0f, 1e-5f);
    EXPECT_NEAR(plan.poses[0].pose.position.y, -8.0f, 1e-5f);  // lifted 8 mm
    ASSERT_EQ(plan.calls.size(), 2u);
    EXPECT_EQ(plan.calls[0].call, Call::compressible);
    EXPECT_EQ(plan.calls[1].call, Call::not_compressible);
    EXPECT_DOUBLE_EQ(plan.calls[0].t_s, plan.poses[3].t_s);  // at the end of the hold
    for (std::size_t i = 1; i < plan.poses.size(); ++i) EXPECT_GT(plan.poses[i].t_s, plan.poses[i - 1].t_s);

    // written and split again: the same calls at the same times
    const SplitScript again = split_exam_script(format_exam_script(plan), "plan.csv");
    ASSERT_EQ(again.calls.size(), 2u);
    EXPECT_DOUBLE_EQ(again.calls[1].t_s, plan.calls[1].t_s);
    EXPECT_EQ(again.calls[1].call, Call::not_compressible);
}

TEST(ExamScript, EachPlannedErrorChangesOnlyItsStation)
{
    const std::vector<StationTruth> stations{station("A", -100), station("B", -120)};
    const ExamScript correct = plan_exam(stations, {10.0, 10.0});
    auto with = [&](PlanError e) { return plan_exam(stations, {10.0, 10.0}, {.error = e, .at = 1}); };

    EXPECT_EQ(with(PlanError::skip).poses.size(), 6u);
    EXPECT_EQ(with(PlanError::skip).calls.size(), 1u);
    EXPECT_NEAR(with(PlanError::light_press).poses[8].pose.position.y, 2.5f, 1e-5f);
    EXPECT_EQ(with(PlanError::light_press).calls[1].call, Call::not_compressible);
    EXPECT_NEAR(with(PlanError::excessive).poses[8].pose.position.y, 18.0f, 1e-5f);
    EXPECT_NEAR(with(PlanError::artery).poses[7].pose.position.x, 15.0f, 1e-4f);
    const Pose tilted = with(PlanError::oblique).poses[7].pose;
    EXPECT_NEAR(std::acos(std::abs(glm::dot(tilted.axis_z(), glm::vec3(0, 0, 1)))) * 180 / 3.14159265, 30.0, 1e-3);
    EXPECT_EQ(with(PlanError::mimic_called).calls[1].call, Call::not_compressible);
    // station A is the same in every plan
    for (PlanError e : {PlanError::skip, PlanError::light_press, PlanError::excessive, PlanError::artery, PlanError::oblique})
        for (int i = 0; i < 6; ++i) EXPECT_EQ(with(e).poses[std::size_t(i)].pose.position, correct.poses[std::size_t(i)].pose.position);
}


// From the front of the thigh to the back of the knee the probe goes round the limb: out along the
// first beam, across, in along the second, never through the leg between them.
TEST(ExamScript, APlannedExamGoesRoundTheLimbBetweenFarTurnedStations)
{
    StationTruth front = station("FV 34", -340), back = station("Popliteal", -420);
    back.ideal_probe.position = glm::vec3(0, 120, -420);
    back.ideal_probe.orientation = glm::angleAxis(3.14159265f, glm::vec3(0, 0, 1));  // beam along -y
    const ExamScript plan = plan_exam({front, back}, {10.0, 10.0});
    // station 1: 6 poses; then out 80 mm along its beam, across to 80 mm off the second, down to 8 mm
    ASSERT_EQ(plan.poses.size(), 14u);
    EXPECT_NEAR(plan.poses[6].pose.position.y, -80.0f, 1e-4f);
    EXPECT_NEAR(plan.poses[7].pose.position.y, 200.0f, 1e-4f);
    EXPECT_NEAR(plan.poses[8].pose.position.y, 128.0f, 1e-4f);
    EXPECT_NEAR(plan.poses[10].pose.position.y, 110.0f, 1e-4f);  // pressed 10 mm along -y
    // neighbouring stations along the thigh do not
    EXPECT_EQ(plan_exam({front, station("FV 32", -320)}, {10.0, 10.0}).poses.size(), 12u);
}

}  // namespace
}  // namespace echosim::exam

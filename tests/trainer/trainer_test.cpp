// The trainer's state without a GPU (trainer/trainer.hpp, lesson.hpp, guidance.hpp): the lessons'
// stations, the guidance's directions from the truth, the screens' keys (the kiosk's Esc), calls
// landing on the station examined, the idle timeout scoring and storing the session.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "exam/records.hpp"
#include "exam/scenario.hpp"
#include "trainer/caliper.hpp"
#include "trainer/guidance.hpp"
#include "trainer/lesson.hpp"
#include "trainer/trainer.hpp"
#include "trainer/trainer_driver.hpp"

namespace echosim {
namespace {

using trainer::Screen;
using ScreenStateRect = trainer::ScreenState::Rect;

ui::UiInput key(ui::Key k)
{
    ui::UiInput in;
    in.pressed = {k};
    return in;
}

trainer::TrainerOptions options(const std::string& name)
{
    trainer::TrainerOptions o;
    o.cases = exam::shipped_cases();
    // the process's id in the name: the same test run by another process at once keeps apart
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / ("trainer_" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    o.records = dir / "records.sqlite";
    o.reports = dir / "reports";
    o.stamp_time = false;
    return o;
}

// a report from the scorer alone (no images): the driver's is tested on the GPU
exam::ExamReport plain_report(const exam::Scorer& s, const std::filesystem::path&, const std::string& trainee)
{
    exam::ExamReport r = s.finish({}, {});
    r.trainee = trainee;
    return r;
}

TEST(TrainerLesson, TheLessonsKeepTheirProtocolsStations)
{
    const exam::Scenario c = exam::read_scenario(exam::shipped_case("healthy"));
    ASSERT_EQ(c.protocol, exam::Protocol::extended);
    const exam::Scenario two = trainer::lesson_scenario(c, exam::Protocol::two_point);
    ASSERT_EQ(two.stations.size(), 2u);
    EXPECT_EQ(two.stations[0].segment, echo::VeinSegment::cfv);
    EXPECT_EQ(two.stations[1].segment, echo::VeinSegment::popliteal);
    EXPECT_EQ(two.protocol, exam::Protocol::two_point);
    const exam::Scenario three = trainer::lesson_scenario(c, exam::Protocol::three_point);
    ASSERT_EQ(three.stations.size(), 3u);
    EXPECT_EQ(three.stations[1].name, "SFJ");
    const exam::Scenario extended = trainer::lesson_scenario(c, exam::Protocol::extended);
    EXPECT_EQ(extended.stations.size(), c.stations.size());
}

TEST(TrainerGuidance, PointsFromTheProbeToTheStationOnTheTruth)
{
    trainer::Trainer t(options("guidance"));
    ASSERT_TRUE(t.select_case("healthy"));
    t.form().lesson = exam::Protocol::extended;
    t.start(0);
    const exam::StationTruth& st = t.scorer().truth()[5];
    const exam::ScoringBands& bands = t.lesson().bands;
    // at the ideal probe: there, nothing to slide or turn
    const trainer::Guidance at = trainer::guide(st.ideal_probe, st, bands);
    EXPECT_TRUE(at.there);
    EXPECT_NEAR(at.along_mm, 0, 1e-3);
    EXPECT_NEAR(at.across_mm, 0, 1e-3);
    EXPECT_NEAR(at.turn_deg, 0, 1e-3);
    // 40 mm further down the leg (towards the knee): slide 40 mm towards the groin
    glm::dvec3 up = st.vein.direction;
    if (up.z < 0) up = -up;
    Pose below = st.ideal_probe;
    below.position -= glm::vec3(40.0 * up);
    const trainer::Guidance g = trainer::guide(below, st, bands);
    EXPECT_FALSE(g.there);
    EXPECT_NEAR(g.along_mm, 40, 0.5);
    EXPECT_NEAR(g.across_mm, 0, 0.5);
    const trainer::GuidanceLevel beginner = trainer::guidance_level(trainer::Difficulty::beginner);
    EXPECT_NE(trainer::guidance_text(g, beginner).find("40 mm towards the groin"), std::string::npos) << trainer::guidance_text(g, beginner);
    // turned 30 degrees about its beam: turn back by 30, the other way
    Pose turned = st.ideal_probe;
    turned.orientation = glm::angleAxis(glm::radians(30.0f), st.ideal_probe.axis_y()) * turned.orientation;
    const trainer::Guidance tg = trainer::guide(turned, st, bands);
    EXPECT_NEAR(std::abs(tg.turn_deg), 30, 0.5);
    EXPECT_FALSE(tg.there);
    // the difficulty fades it: no numbers for an intermediate, nothing for an expert
    const std::string mid = trainer::guidance_text(g, trainer::guidance_level(trainer::Difficulty::intermediate));
    EXPECT_NE(mid.find("towards the groin"), std::string::npos);
    EXPECT_EQ(mid.find("40"), std::string::npos);
    EXPECT_EQ(trainer::guidance_text(g, trainer::guidance_level(trainer::Difficulty::expert)), "");
    EXPECT_EQ(trainer::guidance_level(trainer::Difficulty::expert).arrow_alpha, 0.0f);
}

// A large patient's common femoral vein lies deeper than the 50 mm image the scanner starts with:
// the guidance says how deep (its far wall under the station's ideal probe, from the truth) and to
// deepen the image, at the station and on the way; with the image 70 mm deep it says nothing of it.
// The slim healthy case's CFV is within 50 mm: no such advice.
TEST(TrainerGuidance, SaysToDeepenTheImageWhenTheVeinLiesBelowIt)
{
    const trainer::GuidanceLevel beginner = trainer::guidance_level(trainer::Difficulty::beginner);
    const auto cfv = [](trainer::Trainer& t) -> const exam::StationTruth& {
        t.form().lesson = exam::Protocol::two_point;
        t.start(0);
        return t.scorer().truth()[0];
    };
    trainer::Trainer large(options("large"));
    ASSERT_TRUE(large.select_case("large-patient"));
    const exam::StationTruth& st = cfv(large);
    const trainer::Guidance at = trainer::guide(st.ideal_probe, st, large.lesson().bands);
    const double far = glm::dot(st.vein.centre - glm::dvec3(st.ideal_probe.position), glm::dvec3(st.ideal_probe.axis_y())) + st.vein.radius_mm;
    EXPECT_NEAR(at.vein_far_mm, far, 1e-6);
    EXPECT_GT(at.vein_far_mm, 55.0);
    EXPECT_LT(at.vein_far_mm, kLinearProbe.image_depth_max_mm);
    const std::string text = trainer::guidance_text(at, beginner, 50.0);
    char deep[64];
    std::snprintf(deep, sizeof deep, "The vein lies %.0f mm deep: deepen the image (]).", at.vein_far_mm);
    EXPECT_NE(text.find("At the station"), std::string::npos) << text;
    EXPECT_NE(text.find(deep), std::string::npos) << text;
    EXPECT_EQ(trainer::guidance_text(at, beginner, 70.0).find("deepen"), std::string::npos);
    Pose below = st.ideal_probe;
    below.position -= glm::vec3(0, 0, 40);
    EXPECT_NE(trainer::guidance_text(trainer::guide(below, st, large.lesson().bands), beginner, 50.0).find(deep), std::string::npos);
    EXPECT_NE(trainer::guidance_text(at, trainer::guidance_level(trainer::Difficulty::intermediate), 50.0).find("below the image: deepen it"),
              std::string::npos);

    trainer::Trainer slim(options("slim"));
    ASSERT_TRUE(slim.select_case("healthy"));
    const exam::StationTruth& near = cfv(slim);
    const trainer::Guidance g = trainer::guide(near.ideal_probe, near, slim.lesson().bands);
    EXPECT_LT(g.vein_far_mm, 50.0);
    EXPECT_EQ(trainer::guidance_text(g, beginner, 50.0).find("deepen"), std::string::npos);
}

TEST(TrainerScreens, KeysDriveTheStartScreenAndTheKioskKeepsEsc)
{
    trainer::TrainerOptions o = options("keys");
    trainer::Trainer t(o);
    EXPECT_EQ(t.screen(), Screen::start);
    EXPECT_EQ(t.keys(key(ui::Key::escape), 0, false), trainer::Action::quit);  // not a kiosk: Esc quits
    t.keys(key(ui::Key::f1), 0, false);
    EXPECT_EQ(t.form().lesson, exam::Protocol::two_point);
    t.keys(key(ui::Key::f2), 0, false);
    EXPECT_EQ(t.form().lesson, exam::Protocol::three_point);
    t.keys(key(ui::Key::f5), 0, false);
    EXPECT_EQ(t.form().case_index, 1);
    t.keys(key(ui::Key::f4), 0, false);
    t.keys(key(ui::Key::f4), 0, false);
    EXPECT_EQ(t.form().case_index, int(t.cases().size()) - 1);
    t.keys(key(ui::Key::f6), 0, false);
    EXPECT_EQ(t.form().case_index, -1);
    t.keys(key(ui::Key::f7), 0, false);
    EXPECT_EQ(t.form().difficulty, trainer::Difficulty::intermediate);

    o.kiosk = true;
    trainer::Trainer kiosk(o);
    EXPECT_EQ(kiosk.keys(key(ui::Key::escape), 0, false), trainer::Action::none);
    ui::UiInput combo = key(ui::letter('q'));
    combo.ctrl = combo.alt = true;
    EXPECT_EQ(kiosk.keys(combo, 0, false), trainer::Action::quit);
    // Enter starts; in the exam Esc still does not quit
    EXPECT_EQ(kiosk.keys(key(ui::Key::enter), 1.0, false), trainer::Action::started);
    EXPECT_EQ(kiosk.screen(), Screen::exam);
    EXPECT_EQ(kiosk.keys(key(ui::Key::escape), 1.5, false), trainer::Action::none);
    EXPECT_EQ(kiosk.screen(), Screen::exam);
}

TEST(TrainerScreens, AStartWaitsForItsCasesImagesAndBeginsOnceTheyAreReady)
{
    trainer::Trainer t(options("readiness"));
    t.set_report_maker(plain_report);
    // the case chosen (the first, then the next) is being made; the others are ready
    std::string making = t.cases()[1].id;
    t.set_readiness([&](const exam::Scenario& c) {
        return c.id == making ? trainer::CaseReadiness{false, "being made: 43 %"} : trainer::CaseReadiness{};
    });
    t.keys(key(ui::Key::f5), 0, false);
    EXPECT_FALSE(t.readiness(t.chosen_case()).ready);
    EXPECT_EQ(t.readiness(t.chosen_case()).line, "being made: 43 %");
    EXPECT_EQ(t.keys(key(ui::Key::enter), 1.0, false), trainer::Action::none);
    EXPECT_EQ(t.screen(), Screen::start);
    EXPECT_TRUE(t.start_waiting());
    EXPECT_EQ(t.tick(2.0, false), trainer::Action::none);  // still being made
    EXPECT_EQ(t.screen(), Screen::start);
    making.clear();  // made
    EXPECT_EQ(t.tick(3.0, false), trainer::Action::started);
    EXPECT_EQ(t.screen(), Screen::exam);
    EXPECT_EQ(t.lesson().id, t.cases()[1].id);
    EXPECT_DOUBLE_EQ(t.started_s(), 3.0);
    EXPECT_FALSE(t.start_waiting());
    // a ready case starts at once, and a new lesson forgets a start that waited
    t.finish();
    t.new_lesson();
    EXPECT_EQ(t.keys(key(ui::Key::enter), 4.0, false), trainer::Action::started);
    t.finish();
    t.new_lesson();
    making = t.chosen_case().id;
    EXPECT_EQ(t.request_start(5.0), trainer::Action::none);
    t.finish();  // not in an exam: nothing
    t.new_lesson();
    EXPECT_FALSE(t.start_waiting());
    making.clear();
    EXPECT_EQ(t.tick(6.0, false), trainer::Action::none);
    EXPECT_EQ(t.screen(), Screen::start);
}

// The probe is shown in the middle of the leg's view right of the exam panel: at 1280 x 720 the
// view is the frame left of the image (704 px here), the panel 8..408 px, so the middle of what is
// left is at 556 px, (556 - 352) / 352 = 0.58 of the view's half width right of its centre.
TEST(TrainerScreens, TheProbeShowsBesideTheExamPanelNotUnderIt)
{
    const echo::ImagePlane plane;
    const VkExtent2D extent{1280, 720};
    const float view_w = runner::scene_rect(extent, plane).width * 1280.0f;
    const ScreenStateRect panel{8, 8, 408, 630};
    const glm::vec2 at = trainer::probe_on_screen(panel, extent, plane);
    EXPECT_NEAR(at.x, (0.5f * (408 + view_w) - 0.5f * view_w) / (0.5f * view_w), 1e-5f);
    EXPECT_GT(at.x, 0.3f);
    EXPECT_EQ(at.y, 0.0f);
    EXPECT_EQ(trainer::probe_on_screen(std::nullopt, extent, plane), glm::vec2(0.0f));   // the start and report screens
    const ScreenStateRect wide{8, 8, view_w - 20, 630};                                  // too little left beside it
    EXPECT_EQ(trainer::probe_on_screen(wide, extent, plane), glm::vec2(0.0f));
}

TEST(TrainerScreens, ACallLandsOnTheStationExaminedAndFinishStoresTheSession)
{
    trainer::Trainer t(options("call"));
    t.set_report_maker(plain_report);
    ASSERT_TRUE(t.select_case("healthy"));
    t.form().trainee = "Ada";
    t.form().lesson = exam::Protocol::two_point;
    t.start(0);
    const exam::StationTruth& st = t.scorer().truth()[0];
    EXPECT_EQ(t.target(), std::optional<std::size_t>(0));
    // pressed at the first station at 12 N (in the 8..16 N band) and held (exam::kPressHeldS: four
    // samples at 60 a second), then called
    Pose pressed = pressed_along_beam(st.ideal_probe, 10);
    for (int i = 0; i <= 3; ++i) t.observe({0.5 + i / 60.0, pressed, 12.0, nullptr});
    EXPECT_EQ(t.scorer().current_station(), std::optional<std::size_t>(0));
    EXPECT_FALSE(t.station_done(0));
    // a letter typed into a text field is no call
    t.keys(key(ui::letter('c')), 0.6, true);
    EXPECT_EQ(t.scorer().progress(0).call, exam::Call::none);
    t.keys(key(ui::letter('c')), 0.6, false);
    EXPECT_EQ(t.scorer().progress(0).call, exam::Call::compressible);
    EXPECT_TRUE(t.station_done(0));
    EXPECT_FALSE(t.station_wrong(0));
    EXPECT_EQ(t.target(), std::optional<std::size_t>(1));
    EXPECT_EQ(t.keys(key(ui::Key::end), 0.7, false), trainer::Action::finished);
    EXPECT_EQ(t.screen(), Screen::report);
    EXPECT_EQ(t.report().trainee, "Ada");
    ASSERT_EQ(t.report().stations.size(), 2u);
    EXPECT_TRUE(t.report().stations[0].reached);
    EXPECT_EQ(t.report().stations[0].call, exam::Call::compressible);
    EXPECT_FALSE(t.report().stations[1].reached);
    EXPECT_GT(t.stored_id(), 0);
    ASSERT_EQ(t.earlier().size(), 1u);
    EXPECT_EQ(t.earlier()[0].trainee, "Ada");
    t.keys(key(ui::Key::enter), 1.0, false);
    EXPECT_EQ(t.screen(), Screen::start);
}

TEST(TrainerIdle, TheIdleTimeoutStoresTheSessionAndReturnsToTheStartScreen)
{
    trainer::TrainerOptions o = options("idle");
    o.idle_timeout_s = 10;
    o.kiosk = true;
    trainer::Trainer t(o);
    t.set_report_maker(plain_report);
    t.form().trainee = "Idle Ida";
    t.start(0);
    t.observe({0.1, t.scorer().truth()[0].ideal_probe, 0.0, nullptr});
    EXPECT_EQ(t.tick(0.1, true), trainer::Action::none);
    // the probe still, no input: nothing happens before the timeout...
    EXPECT_EQ(t.tick(9.0, false), trainer::Action::none);
    EXPECT_EQ(t.screen(), Screen::exam);
    // ...and at it the session is scored, stored and the start screen shown
    EXPECT_EQ(t.tick(10.2, false), trainer::Action::finished);
    EXPECT_EQ(t.screen(), Screen::start);
    EXPECT_NE(t.message().find("idle"), std::string::npos);
    exam::Records records(o.records, {.create = false});
    const std::vector<exam::SessionRecord> stored = records.sessions("Idle Ida");
    ASSERT_EQ(stored.size(), 1u);
    EXPECT_EQ(stored[0].case_id, t.lesson().id);
}

// The image panel of a 1280 x 720 frame and the default plane (40 mm wide, 50 deep), worked by
// hand: the panel keeps the plane's aspect at the frame's full height, 720 px for 50 mm, so
// 14.4 px/mm both ways and 576 px wide, against the frame's right edge (x from 704).
TEST(TrainerCaliper, TheImagePanelsPixelsAreTheImagesMillimetres)
{
    const trainer::ImagePanel panel = trainer::image_panel({1280, 720}, echo::ImagePlane{});
    EXPECT_FLOAT_EQ(panel.x, 704.0f);
    EXPECT_FLOAT_EQ(panel.y, 0.0f);
    EXPECT_FLOAT_EQ(panel.width, 576.0f);
    EXPECT_FLOAT_EQ(panel.height, 720.0f);
    const std::optional<glm::dvec2> centre = trainer::image_point_at(panel, {704.0f + 288.0f, 360.0f});
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->x, 0.0, 1e-9);
    EXPECT_NEAR(centre->y, 25.0, 1e-9);
    const std::optional<glm::dvec2> corner = trainer::image_point_at(panel, {704.0f, 720.0f});
    ASSERT_TRUE(corner);
    EXPECT_NEAR(corner->x, -20.0, 1e-9);
    EXPECT_NEAR(corner->y, 50.0, 1e-9);
    // off the image: the leg's view, above or below it, a NaN cursor
    EXPECT_FALSE(trainer::image_point_at(panel, {703.0f, 360.0f}));
    EXPECT_FALSE(trainer::image_point_at(panel, {900.0f, 721.0f}));
    EXPECT_FALSE(trainer::image_point_at(panel, {std::nanf(""), 360.0f}));
    // drawn where it was clicked
    const glm::vec2 back = trainer::pixel_of(panel, {3.5, 12.25});
    EXPECT_NEAR(back.x, 704.0f + 14.4f * (20.0f + 3.5f), 1e-3f);
    EXPECT_NEAR(back.y, 14.4f * 12.25f, 1e-3f);
}

TEST(TrainerCaliper, TwoClicksMeasureAndAThirdStartsAnew)
{
    trainer::Caliper c;
    EXPECT_FALSE(c.distance_mm());
    c.click({-3.0, 10.0});
    EXPECT_FALSE(c.distance_mm());
    c.click({1.0, 13.0});
    ASSERT_TRUE(c.distance_mm());
    EXPECT_NEAR(*c.distance_mm(), 5.0, 1e-12);  // a 3-4-5 triangle
    c.click({0.0, 0.0});
    EXPECT_FALSE(c.distance_mm());
    ASSERT_TRUE(c.first());
    EXPECT_EQ(*c.first(), glm::dvec2(0.0, 0.0));
    c.clear();
    EXPECT_FALSE(c.first());
}

}  // namespace
}  // namespace echosim

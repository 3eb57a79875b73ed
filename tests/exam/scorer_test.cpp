// The scorer judged on synthetic exams whose truth is known by construction: a straight vein along
// z 25 mm under the skin, its artery 15 mm beside it, stations on it; each test makes one error (or
// none) and expects exactly that error.
#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "echo/phantom.hpp"
#include "exam/scorer.hpp"

namespace echosim::exam {
namespace {

constexpr double kDepth = 25.0;   // vein below the face [mm]
constexpr double kArteryX = 15.0; // artery beside it along the array [mm]

StationTruth station(const char* name, double z, bool thrombosed = false, bool mimic = false)
{
    StationTruth t;
    t.name = name;
    t.segment = echo::VeinSegment::fv;
    t.s_cm = -z / 10;
    t.vein = {glm::dvec3(0, kDepth, z), glm::dvec3(0, 0, 1), 4.0};
    t.artery = {glm::dvec3(kArteryX, kDepth, z), glm::dvec3(0, 0, 1), 3.5};
    t.thrombosed = thrombosed;
    t.mimic_nearby = mimic;
    t.ideal_probe.position = glm::vec3(0, 0, float(z));
    return t;
}

Scenario scenario()
{
    Scenario s;
    s.id = "synthetic";
    s.bands.adequate_force_N = 5;
    s.bands.excessive_force_N = 30;
    return s;
}

Pose at(double x, double z, double tilt_deg = 0)
{
    Pose p;
    p.position = glm::vec3(float(x), 0, float(z));
    // a tilt about the array's axis turns the plane away from transverse
    p.orientation = glm::angleAxis(float(tilt_deg * std::numbers::pi / 180), glm::vec3(1, 0, 0));
    return p;
}

// Presses at `pose` up to `peak` N over 1 s (100 samples) and back, from `t0` [s], the image
// `image_depth_mm` deep; returns the end time.
double press(Scorer& scorer, const Pose& pose, double peak, double t0, double image_depth_mm = kLinearProbe.image_depth_mm)
{
    echo::EchoFrame frame;
    frame.face = pose;
    for (int i = 0; i <= 100; ++i) {
        const double t = t0 + 0.02 * i;
        const double f = peak * (i <= 50 ? i / 50.0 : (100 - i) / 50.0);
        frame.time_s = t;
        scorer.observe({t, pose, f, &frame, image_depth_mm});
    }
    return t0 + 2.0;
}

// The deepest press press() makes: the highest force held kPressHeldS, over samples 0.02 s apart
// on its triangle (8 N at its top): the least of the four samples that span 0.05 s round the top
// (two 0.02 s steps down from it), 8 * 48 / 50.
constexpr double kHeldOf8 = 8.0 * 48 / 50;

std::vector<ErrorKind> kinds(const ExamReport& r)
{
    std::vector<ErrorKind> k;
    for (const FlaggedError& e : r.errors) k.push_back(e.kind);
    return k;
}

ExamReport finish(const Scorer& s) { return s.finish({}, {}); }

TEST(Scorer, CorrectExamHasNoErrorsAndFindsTheClot)
{
    Scorer s(scenario(), {station("FV 10", -100), station("FV 12", -120, true)});
    double t = press(s, at(0, -100), 8, 0);
    s.call(t, Call::compressible);
    t = press(s, at(0, -120), 8, t);
    s.call(t, Call::not_compressible);
    const ExamReport r = finish(s);
    EXPECT_TRUE(r.errors.empty()) << error_name(r.errors.front().kind) << ": " << r.errors.front().detail;
    ASSERT_EQ(r.stations.size(), 2u);
    EXPECT_TRUE(r.stations[0].reached && r.stations[1].reached);
    EXPECT_NEAR(r.stations[0].peak_force_N, kHeldOf8, 1e-9);
    EXPECT_DOUBLE_EQ(r.score, 1.0);
    EXPECT_TRUE(r.passed);
    EXPECT_NE(r.conclusion.find("FV 12"), std::string::npos) << r.conclusion;
    EXPECT_DOUBLE_EQ(r.osaus.decision, 5);
    // the case's bands, for the report's force trace
    EXPECT_DOUBLE_EQ(r.adequate_force_N, 5);
    EXPECT_DOUBLE_EQ(r.excessive_force_N, 30);
    // the path: from the first station to the second, 20 mm
    EXPECT_NEAR(r.motion.path_mm, 20.0, 1e-3);
}

// The vein must be in the image the trainee sees: under a large patient's fat, 55 mm down, it is
// below a 50 mm image (the station not reached, skipped, though the probe pressed right over it)
// and within a 70 mm one (reached, no error).
TEST(Scorer, AVeinBelowTheImageIsNotReached)
{
    StationTruth deep = station("CFV", -100);
    deep.vein.centre.y = deep.artery.centre.y = 55.0;
    for (const double depth : {50.0, 70.0}) {
        SCOPED_TRACE(depth);
        Scorer s(scenario(), {deep});
        s.call(press(s, at(0, -100), 8, 0, depth), Call::compressible);
        const ExamReport r = finish(s);
        ASSERT_EQ(r.stations.size(), 1u);
        EXPECT_EQ(r.stations[0].reached, depth > 55.0);
        if (depth > 55.0) EXPECT_TRUE(r.errors.empty()) << error_name(r.errors.front().kind);
        else EXPECT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::skipped_station});
    }
}

// A station's report image reaches below the vein's lumen at rest (kStationImageMarginMm): as deep
// as the trainee's image at the deepest press, deeper a centimetre at a time when the vein at rest
// under the pressed face would be cut off, never past the probe's deepest; and the depth kept is
// the trainee's at the deepest press, not at the last sample.
TEST(Scorer, AStationsReportImageHoldsTheVeinsLumenAtRest)
{
    StationTruth t = station("CFV", -100);  // the face's beam along +y; the vein 25 mm down, radius 4
    echo::EchoFrame f;
    f.face = at(0, -100);
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 50), 50.0);   // 25 + 4 + 3 = 32 mm needed
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 40), 40.0);   // the trainee's own shallower image
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 30), 40.0);   // 30 would cut it: one step
    t.vein.centre.y = 48.0;                                      // 48 + 4 + 3 = 55 mm
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 50), 60.0);
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 70), 70.0);
    t.vein.centre.y = 90.0;                                      // past the probe's reach: its deepest
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 50), kLinearProbe.image_depth_max_mm);
    // pressed in, the face nearer the vein: what lies below it at rest is nearer too
    t.vein.centre.y = 48.0;
    f.face.position.y = 10.0f;
    EXPECT_DOUBLE_EQ(station_image_depth_mm(t, f, 50), 50.0);

    Scorer s(scenario(), {station("FV 10", -100)});
    press(s, at(0, -100), 8, 0, 60.0);
    press(s, at(0, -100), 4, 2.0, 40.0);  // a lighter press later, with a shallower image
    EXPECT_DOUBLE_EQ(s.deepest_image_depth_mm(0), 60.0);
}

// The deepest press is one held (kPressHeldS): a light press with one sample's jab far above it
// (a spike of the hand, or of the contact) is judged at the force held, with the image of the held
// press; a press held at the jab's force is judged at it.
TEST(Scorer, AJabIsNotTheDeepestPress)
{
    Scorer s(scenario(), {station("FV 10", -100)});
    echo::EchoFrame frame;
    frame.face = at(0, -100);
    const auto sample = [&](double t, double force) {
        frame.time_s = t;
        s.observe({t, frame.face, force, &frame, kLinearProbe.image_depth_mm});
    };
    for (int i = 0; i <= 60; ++i) sample(i / 60.0, i == 30 ? 12.0 : 3.0);  // 3 N held a second, 12 N at 0.5 s
    s.call(1.0, Call::compressible);
    ExamReport r = finish(s);
    EXPECT_NEAR(r.stations[0].peak_force_N, 3.0, 1e-12);
    EXPECT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::too_little_pressure});
    ASSERT_TRUE(s.deepest_frame(0));
    EXPECT_LT(s.deepest_frame(0)->time_s, 0.5);  // the held press's image, at its first 0.05 s
    // held: 12 N for four samples (0.05 s) is the press judged
    for (int i = 61; i <= 64; ++i) sample(i / 60.0, 12.0);
    r = finish(s);
    EXPECT_NEAR(r.stations[0].peak_force_N, 12.0, 1e-12);
    EXPECT_NEAR(s.deepest_frame(0)->time_s, 64 / 60.0, 1e-12);
    EXPECT_TRUE(r.errors.empty()) << error_name(r.errors.front().kind);
}

TEST(Scorer, TooLittlePressureOnly)
{
    Scorer s(scenario(), {station("FV 10", -100)});
    s.call(press(s, at(0, -100), 3, 0), Call::compressible);
    const ExamReport r = finish(s);
    EXPECT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::too_little_pressure});
    EXPECT_NEAR(r.score, 2.0 / 3.0, 1e-12);  // reached and called right, not adequately pressed
}

// Adequate pressure is the walls meeting (kWallsMetRatio), whatever the force took: 3 N (under the
// band's 5) that closed the vein to 4 % of its lumen is pressed enough; the same 3 N leaving half
// of it open, or a thrombosed vein's 12 %, is too little, and the message says the walls did not meet.
TEST(Scorer, AVeinWhoseWallsMetUnderTheBandWasPressedEnough)
{
    const auto scored = [](double pressed_mm2, bool thrombosed) {
        Scorer s(scenario(), {station("FV 10", -100, thrombosed)});
        s.call(press(s, at(0, -100), 3, 0), thrombosed ? Call::not_compressible : Call::compressible);
        Compression c;
        c.vein_rest_mm2 = 50;
        c.vein_pressed_mm2 = pressed_mm2;
        return s.finish({c}, {""});
    };
    const ExamReport closed = scored(2, false);
    EXPECT_TRUE(closed.errors.empty()) << closed.errors.front().detail;
    EXPECT_DOUBLE_EQ(closed.score, 1.0);
    EXPECT_NEAR(closed.stations[0].collapse_ratio, 0.04, 1e-12);
    const ExamReport open = scored(25, false);
    ASSERT_EQ(kinds(open), std::vector<ErrorKind>{ErrorKind::too_little_pressure});
    EXPECT_NE(open.errors[0].detail.find("walls did not meet (lumen 50 % of rest)"), std::string::npos) << open.errors[0].detail;
    EXPECT_NEAR(open.score, 2.0 / 3.0, 1e-12);
    // just over the line: 10 % is met, 12 % is not
    EXPECT_TRUE(scored(5, false).errors.empty());
    EXPECT_EQ(kinds(scored(6, true)), std::vector<ErrorKind>{ErrorKind::too_little_pressure});
}

TEST(Scorer, ExcessiveForceOnly)
{
    Scorer s(scenario(), {station("FV 10", -100)});
    s.call(press(s, at(0, -100), 40, 0), Call::compressible);
    EXPECT_EQ(kinds(finish(s)), std::vector<ErrorKind>{ErrorKind::excessive_force});
}

// Excessive is a force held past the limit (kExcessiveHoldS, 50 ms), not one sample's spike: a press
// at 20 N (band 5..30) with one sample of 45 N in it is not flagged, nor two samples 20 ms apart
// (held 20 ms); the same press holding 35 N for 60 ms is, from when it went past, with how long.
TEST(Scorer, ExcessiveIsAForceHeldNotASpike)
{
    const auto scored = [](const std::vector<std::pair<double, double>>& over) {  // (time, force) replacing the press's
        Scorer s(scenario(), {station("FV 10", -100)});
        echo::EchoFrame frame;
        frame.face = at(0, -100);
        for (int i = 0; i <= 100; ++i) {
            const double t = 0.02 * i;
            double f = i <= 50 ? 20.0 * i / 50.0 : 20.0 * (100 - i) / 50.0;
            for (const auto& [when, force] : over)
                if (std::abs(when - t) < 1e-9) f = force;
            frame.time_s = t;
            s.observe({t, frame.face, f, &frame});
        }
        s.call(2.0, Call::compressible);
        return finish(s);
    };
    EXPECT_TRUE(scored({{1.0, 45.0}}).errors.empty());
    EXPECT_TRUE(scored({{1.0, 45.0}, {1.02, 40.0}}).errors.empty());
    const ExamReport held = scored({{0.96, 35.0}, {0.98, 35.0}, {1.0, 35.0}, {1.02, 35.0}});
    ASSERT_EQ(kinds(held), std::vector<ErrorKind>{ErrorKind::excessive_force});
    EXPECT_NEAR(held.errors[0].time_s, 0.96, 1e-9);
    EXPECT_NE(held.errors[0].detail.find("held there 0.06 s"), std::string::npos) << held.errors[0].detail;
    EXPECT_NEAR(held.score, 2.0 / 3.0, 1e-12);  // reached and called right, not pressed within the band
    EXPECT_NEAR(held.stations[0].peak_force_N, 35.0, 1e-9);
}

TEST(Scorer, SkippedStationOnly)
{
    Scorer s(scenario(), {station("FV 10", -100), station("FV 12", -120)});
    s.call(press(s, at(0, -100), 8, 0), Call::compressible);
    const ExamReport r = finish(s);
    ASSERT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::skipped_station});
    EXPECT_EQ(r.errors[0].station, "FV 12");
    EXPECT_FALSE(r.stations[1].reached);
    EXPECT_NE(r.conclusion.find("Incomplete"), std::string::npos);
}

// A vein rising 20 degrees towards the skin down the limb under a thick layer (40 mm down at FV 10,
// stations 20 mm apart along it): the face over FV 10 projects 40 sin 20 = 13.7 mm along the
// vessel's own line, past the tolerance, and within 10 mm of the next station (6.3 mm short of it),
// where it was scored; carried along the station's way in, it is at FV 10, and the press and the
// call are FV 10's alone.
TEST(Scorer, APressOverASlopingVeinIsScoredAtItsOwnStation)
{
    constexpr double kDeep = 40, kSlope = 20 * std::numbers::pi / 180;
    const glm::dvec3 along(0, -std::sin(kSlope), -std::cos(kSlope));  // down the limb (-z), nearer the skin (-y)
    std::vector<StationTruth> stations;
    for (int k = 0; k < 2; ++k) {
        StationTruth t = station(k == 0 ? "FV 10" : "FV 12", -100);
        const glm::dvec3 centre = glm::dvec3(0, kDeep, -100) + 20.0 * k * along;
        t.vein = {centre, along, 4.0};
        t.artery = {centre + glm::dvec3(kArteryX, 0, 0), along, 3.5};
        t.ideal_probe.position = glm::vec3(float(centre.x), 0, float(centre.z));
        stations.push_back(t);
    }
    // a probe transverse to the vein: its plane's normal along the vein
    const Pose over = at(0, -100, -20);
    Scorer s(scenario(), stations);
    s.call(press(s, over, 8, 0), Call::compressible);
    const ExamReport r = finish(s);
    EXPECT_TRUE(r.stations[0].reached);
    EXPECT_NEAR(r.stations[0].peak_force_N, kHeldOf8, 1e-9);
    EXPECT_EQ(r.stations[0].call, Call::compressible);
    EXPECT_FALSE(r.stations[1].reached);
    EXPECT_EQ(r.stations[1].peak_force_N, 0);
    EXPECT_EQ(r.stations[1].call, Call::none);
}

TEST(Scorer, ObliquePlaneOnly)
{
    Scorer s(scenario(), {station("FV 10", -100)});
    s.call(press(s, at(0, -100, 30), 8, 0), Call::compressible);
    const ExamReport r = finish(s);
    EXPECT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::oblique_plane});
    EXPECT_FALSE(r.stations[0].reached);
    EXPECT_NEAR(r.stations[0].angle_deg, 30.0, 0.01);
}

TEST(Scorer, ArteryPressedInsteadOfTheVein)
{
    Scorer s(scenario(), {station("CFV", -100)});
    s.call(press(s, at(kArteryX, -100), 8, 0), Call::compressible);
    const ExamReport r = finish(s);
    ASSERT_EQ(kinds(r), std::vector<ErrorKind>{ErrorKind::wrong_vessel}) << r.errors.size();
    EXPECT_NE(r.errors[0].detail.find("artery"), std::string::npos);
}

TEST(Scorer, LymphNodeCalledAClotAndAMissedClotFails)
{
    Scorer s(scenario(), {station("CFV", -100, false, true), station("FV 12", -120, true)});
    double t = press(s, at(0, -100), 8, 0);
    s.call(t, Call::not_compressible);
    t = press(s, at(0, -120), 8, t);
    s.call(t, Call::compressible);
    const ExamReport r = finish(s);
    EXPECT_EQ(kinds(r), (std::vector<ErrorKind>{ErrorKind::mimic_called_clot, ErrorKind::wrong_call}));
    EXPECT_FALSE(r.passed);  // a thrombosed station called compressible fails whatever the score
}

// The vein's interior counted in the labels: a disc of radius 4 mm at rest, squeezed to an ellipse
// of half-height 0.4 mm under the press; 0.1 mm pixels.
TEST(Scorer, CompressionIsMeasuredInTheDeformedLabels)
{
    echo::ImagePlane plane;
    plane.columns = 400;
    plane.rows = 500;  // 0.1 x 0.1 mm
    const StationTruth truth = station("FV 10", -100);
    auto imager = [&](const echo::EchoFrame& f) {
        std::vector<std::uint8_t> labels(plane.pixels(), std::uint8_t(echo::Tissue::muscle));
        const double half_height = f.columns.empty() ? 4.0 : 0.4;
        for (std::uint32_t r = 0; r < plane.rows; ++r)
            for (std::uint32_t c = 0; c < plane.columns; ++c) {
                const double x = (c + 0.5) * plane.pixel_x_mm() - plane.width_mm / 2, y = (r + 0.5) * plane.pixel_y_mm();
                const double vx = x / 4.0, vy = (y - kDepth) / half_height;
                const double ax = (x - kArteryX) / 3.5, ay = (y - kDepth) / 3.5;
                if (vx * vx + vy * vy <= 1) labels[r * plane.columns + c] = std::uint8_t(echo::Tissue::vein_lumen);
                if (ax * ax + ay * ay <= 1) labels[r * plane.columns + c] = std::uint8_t(echo::Tissue::artery_lumen);
            }
        return labels;
    };
    echo::EchoFrame pressed;
    pressed.face = at(0, -100);
    pressed.columns.resize(plane.columns);
    const Compression c = measure_compression(truth, pressed, plane, imager);
    const double pi = std::numbers::pi;
    EXPECT_NEAR(c.vein_rest_mm2, pi * 16, 0.02 * pi * 16);
    EXPECT_NEAR(c.vein_pressed_mm2, pi * 4 * 0.4, 0.05 * pi * 1.6);
    // the artery beside it: the same at rest and pressed, and never counted as the vein
    EXPECT_NEAR(c.artery_rest_mm2, pi * 3.5 * 3.5, 0.02 * pi * 12.25);
    EXPECT_DOUBLE_EQ(c.artery_pressed_mm2, c.artery_rest_mm2);
}

}  // namespace
}  // namespace echosim::exam

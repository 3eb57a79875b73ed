// The runner (runner/runner.hpp): every configuration (exam, soak, haptics-demo; `run` in the
// window smoke test and the build check one_loop.cmake) steps through Runner::step, counted by an
// observer; the exam's frames are the same bytes run after run; the frame's passes come in their
// order and a configuration extends them; the image panel says when there is nothing to image.
// GPU tests on lavapipe with validation on (test_gpu.hpp): any message fails them.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "app/haptics_demo.hpp"
#include "app/soak.hpp"
#include "echo/echo_test_volumes.hpp"
#include "io/png.hpp"
#include "runner/exam_config.hpp"
#include "runner/guide_pass.hpp"
#include "runner/image_cue.hpp"
#include "runner/recorders.hpp"
#include "runner/runner.hpp"
#include "runner/scanner_controls.hpp"
#include "test_gpu.hpp"

namespace echosim {
namespace {

// Counts what the runner hands its observers.
struct StepCounter final : runner::Observer {
    runner::Runner* attached = nullptr;
    std::int64_t steps = 0, frames = 0, finishes = 0, last_step = -1;
    bool in_order = true;
    void on_attach(runner::Runner& r) override { attached = &r; }
    void on_step(runner::StepContext& step) override
    {
        in_order = in_order && step.step == last_step + 1;
        last_step = step.step;
        ++steps;
    }
    void on_frame(const runner::FrameContext& frame) override { frames += frame.shown ? 1 : 0; }
    void on_finish(const runner::FinishContext& end) override
    {
        ++finishes;
        in_order = in_order && end.steps == steps;
    }
};

struct TestVolumes {
    std::shared_ptr<const io::Volume> grey, labels;
};
TestVolumes small_volume()
{
    const scene::LegModel leg;
    test::LabelledVolume v = test::phantom_volume(leg, echo::Case::healthy, leg.probe_rest_pose(0.5f, 0.5f), 0.6);
    return {std::make_shared<const io::Volume>(std::move(v.grey)), std::make_shared<const io::Volume>(std::move(v.labels))};
}

std::string file_bytes(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// A probe placed by the test before each advance: resting at `rest`, pressed towards `press_mm`
// by at most 0.5 mm a step (30 mm/s at 60 steps a second: a hand's pace).
struct PlaceProbe final : runner::Input {
    Pose rest;
    double press_mm = 0;
    double now_mm = 0;
    bool poll(runner::Runner& r, double) override
    {
        now_mm = std::min(press_mm, now_mm + 0.5);
        r.session().place_probe({rest, now_mm});
        return true;
    }
};

runner::ExamOptions small_exam(const TestVolumes& v)
{
    runner::ExamOptions o;
    o.volume = v.grey;
    o.labels = v.labels;
    o.gpu = test::lavapipe_options();
    o.extent = {192, 108};
    return o;
}

TEST(RunnerConfigurations, TheExamStepsThroughTheRunnerAndWritesFramesAtItsRate)
{
    const TestVolumes v = small_volume();
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "runner_exam_rate";
    std::filesystem::remove_all(dir);
    auto counter = std::make_shared<StepCounter>();
    std::vector<std::filesystem::path> written;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::ExamOptions o = small_exam(v);
        o.duration_s = 0.1;  // 6 steps of 1/60 s
        o.frames_per_s = 30;
        o.frames_dir = dir;
        o.observers.push_back(counter);
        runner::Runner r(runner::exam_config(std::move(o)));
        messages = r.validation_counter();
        EXPECT_EQ(counter->attached, &r);
        EXPECT_EQ(r.session().clock(), session::Clock::lock_step);
        r.run();
        EXPECT_FALSE(r.step());  // ended, and stays so
        EXPECT_EQ(r.steps(), 6);
        EXPECT_NEAR(r.session().time(), 0.1, 1e-9);
        // frame k at the first step at or after k/30 s (steps end at 1/60, 2/60, ... 6/60 s): at
        // 1/60, 2/60, 4/60 and 6/60 s; drawn only when the recorder asks
        EXPECT_EQ(r.frames(), 4);
    }
    EXPECT_EQ(counter->steps, 6);
    EXPECT_EQ(counter->frames, 4);
    EXPECT_EQ(counter->finishes, 1);
    EXPECT_TRUE(counter->in_order);
    for (int k = 0; k < 4; ++k) {
        const io::RgbaImage png = io::read_png(dir / runner::FrameRecorder::file_name(k));
        EXPECT_EQ(png.width, 192u);
        EXPECT_EQ(png.height, 108u);
    }
    EXPECT_FALSE(std::filesystem::exists(dir / runner::FrameRecorder::file_name(4)));
    EXPECT_EQ(messages->load(), 0u);
    std::filesystem::remove_all(dir);
}

// An exam that draws nothing (draws false: `echosim exam --frames-per-s 0`) makes no GPU object, and
// its session steps as the drawing one's does: the same probe forces and tissue, step by step
// (drawing reads the session, never moves it). Frames asked for with drawing off are refused.
TEST(RunnerConfigurations, AnExamThatDrawsNothingMakesNoGpuObjectAndStepsTheSame)
{
    const TestVolumes v = small_volume();
    std::vector<double> forces[2];
    for (const bool draws : {true, false}) {
        runner::ExamOptions o = small_exam(v);
        o.duration_s = 0.25;
        o.draws = draws;
        runner::Runner r(runner::exam_config(std::move(o)));
        EXPECT_EQ(r.context() == nullptr, !draws);
        EXPECT_EQ(r.frame() == nullptr, !draws);
        // the probe pressed in over the run, so the force moves
        session::ProbePlacement placement = r.session().probe();
        for (int step = 0; r.step(); ++step) {
            forces[draws ? 0 : 1].push_back(r.session().view().probe_force_N);
            placement.press_mm = 0.5 * (step + 1);
            r.session().place_probe(placement);
        }
        EXPECT_EQ(r.frames(), 0);  // no observer asked for one
    }
    ASSERT_EQ(forces[0].size(), 15u);
    EXPECT_GT(forces[0].back(), 0.5) << "the probe never pressed";
    EXPECT_EQ(forces[0], forces[1]);
    runner::ExamOptions frames_without_drawing = small_exam(v);
    frames_without_drawing.duration_s = 0.1;
    frames_without_drawing.draws = false;
    frames_without_drawing.frames_per_s = 10;
    frames_without_drawing.frames_dir = testing::TempDir();
    EXPECT_THROW(runner::exam_config(std::move(frames_without_drawing)), std::invalid_argument);
}

// The frames are written on the recorder's own thread: a frame that cannot be written (its name
// taken by a folder) still ends the run with an error naming the file, the frames before it kept.
TEST(RunnerConfigurations, AFrameThatCannotBeWrittenEndsTheRunNamingIt)
{
    const TestVolumes v = small_volume();
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "runner_frame_fault";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / runner::FrameRecorder::file_name(2));
    runner::ExamOptions o = small_exam(v);
    o.duration_s = 0.2;
    o.frames_per_s = 30;
    o.frames_dir = dir;
    try {
        runner::Runner r(runner::exam_config(std::move(o)));
        r.run();
        ADD_FAILURE() << "the run ended without the write's error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(runner::FrameRecorder::file_name(2)), std::string::npos) << e.what();
    }
    for (int k = 0; k < 2; ++k) EXPECT_NO_THROW(io::read_png(dir / runner::FrameRecorder::file_name(k))) << "frame " << k;
    EXPECT_TRUE(std::filesystem::is_directory(dir / runner::FrameRecorder::file_name(2)));
    std::filesystem::remove_all(dir);
}

TEST(RunnerConfigurations, TheHapticsDemoStepsThroughTheRunnerOneStepATick)
{
    app::SlideScript script;
    script.approach_s = 0.05;
    script.hold_s = 0.02;
    script.slide_s = 0.1;
    auto counter = std::make_shared<StepCounter>();
    const app::Fig8Result r = app::run_fig8(script, 100.0, {counter});
    ASSERT_GT(r.rows.size(), 100u);
    EXPECT_EQ(counter->steps, std::int64_t(r.rows.size()));  // one row a step, each made in the runner's step
    EXPECT_EQ(counter->frames, 0);                           // no frame: no GPU
    EXPECT_EQ(counter->finishes, 1);
    EXPECT_TRUE(counter->in_order);
    EXPECT_NEAR(r.rows.back().t_s, double(r.rows.size()) * 1e-3, 1e-9);  // lock-step, a tick a step
}

TEST(RunnerConfigurations, TheSoakStepsThroughTheRunnerEveryStepAFrame)
{
    app::SoakOptions o;
    o.seconds = 0.5;
    o.gpu = test::lavapipe_options();
    o.width = 160;
    o.height = 96;
    o.deadlines = app::DeadlineCheck::report;
    const TestVolumes v = small_volume();
    o.volumes = {v.grey, v.labels, "the test volume"};
    auto counter = std::make_shared<StepCounter>();
    o.observers.push_back(counter);
    const app::SoakResult r = app::run_soak_session(o);
    ASSERT_GT(r.frames, 0);
    EXPECT_EQ(counter->frames, r.frames);
    EXPECT_EQ(counter->steps, r.frames);  // a frame every step, offscreen, never skipped
    EXPECT_EQ(counter->finishes, 1);
    EXPECT_TRUE(counter->in_order);
    EXPECT_EQ(r.validation_messages, 0u);
    EXPECT_FALSE(r.samples.empty());
}

// The camera keeps the probe in frame when the configuration says so (RunnerConfig::
// camera_follows_probe, as `run` does): after 2 s (about six of OrbitCamera::kFollowS) its target
// is on the probe, within 0.3 % of where it started from; a configuration that does not ask keeps
// the default view.
TEST(Runner, TheCameraFollowsTheProbeWhenAsked)
{
    for (bool follows : {true, false}) {
        runner::RunnerConfig c;
        c.max_steps = 120;
        c.lock_step_dt_s = 1.0 / 60;
        c.camera_follows_probe = follows;
        runner::Runner r(c);
        const glm::vec3 start = r.scene().camera.target;
        r.run();
        const glm::vec3 probe = r.session().view().probe.position;
        ASSERT_GT(glm::distance(start, probe), 50.0f) << "the default view's target is not already on the probe";
        if (follows)
            EXPECT_LT(glm::distance(r.scene().camera.target, probe), 0.004f * glm::distance(start, probe));
        else
            EXPECT_EQ(r.scene().camera.target, start);
    }
}

TEST(Runner, RefusesAConfigurationItCannotRunNamingTheField)
{
    runner::RunnerConfig c;
    c.lock_step_dt_s = 0;
    try {
        runner::Runner r(c);
        ADD_FAILURE() << "a zero step was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("lock_step_dt_s"), std::string::npos) << e.what();
    }
    runner::RunnerConfig frame;
    frame.output = runner::Output::offscreen;
    try {
        runner::Runner r(frame);
        ADD_FAILURE() << "a frame without a volume was made";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("volume"), std::string::npos) << e.what();
    }
    EXPECT_THROW(runner::exam_config({}), std::invalid_argument);  // no trajectory, no duration
    // generative imaging synthesises from the labels: a volume without them cannot be imaged so
    const TestVolumes v = small_volume();
    runner::ExamOptions unlabelled = small_exam(v);
    unlabelled.labels = nullptr;
    unlabelled.duration_s = 0.1;
    unlabelled.imaging = echo::Imaging::generative;
    try {
        runner::Runner r(runner::exam_config(std::move(unlabelled)));
        ADD_FAILURE() << "a generative image without labels was made";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("imaging"), std::string::npos) << e.what();
    }
}

// Unset, the imaging is the machine's: interpolative on lavapipe (a CPU device), where generative
// imaging halves the frame rate; asked for, generative is made there too, its frames drawn clean.
TEST(Runner, TheImagingIsTheMachinesUnlessTheConfigurationSays)
{
    const TestVolumes v = small_volume();
    for (const auto asked : {std::optional<echo::Imaging>{}, std::optional(echo::Imaging::generative)}) {
        runner::ExamOptions o = small_exam(v);
        o.duration_s = 2.0 / 60;
        o.imaging = asked;
        runner::Runner r(runner::exam_config(std::move(o)));
        EXPECT_EQ(r.imaging(), asked.value_or(echo::Imaging::interpolative));
        const echo::Imaging shown = r.frame()->echo_image().imaging();
        EXPECT_EQ(shown, r.imaging());
        r.run();
        EXPECT_EQ(r.validation_counter()->load(), 0u);
    }
}

// A pass a configuration adds: draws nothing, names itself, counts the frames it is set up for.
struct NamedPass final : runner::SessionPass {
    explicit NamedPass(const char* n) : n_(n) {}
    const char* name() const override { return n_; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::none(); }
    void record(const gpu::PassContext&) override { ++recorded; }
    void set(const session::SessionView& state, VkExtent2D) override
    {
        ++set_up;
        last_time_s = state.time_s;
    }
    const char* n_;
    int recorded = 0, set_up = 0;
    double last_time_s = -1;
};

TEST(Runner, TheFramesPassesComeInOrderAndAConfigurationExtendsThem)
{
    const TestVolumes v = small_volume();
    runner::ExamOptions o = small_exam(v);
    o.duration_s = 2.0 / 60.0;
    runner::RunnerConfig c = runner::exam_config(std::move(o));
    NamedPass* ui = nullptr;
    const auto make = [](const char* name, NamedPass** keep) {
        return [name, keep](const runner::PassSetup&) {
            auto p = std::make_unique<NamedPass>(name);
            if (keep) *keep = p.get();
            return std::unique_ptr<gpu::FramePass>(std::move(p));
        };
    };
    c.passes.push_back({runner::PassPlace::overlay, make("ui", &ui)});
    c.passes.push_back({runner::PassPlace::image, make("b-mode", nullptr)});
    c.passes.push_back({runner::PassPlace::after_scene, make("probe shadow", nullptr)});
    c.drawing = runner::Drawing::every_step;
    runner::Runner r(std::move(c));
    const std::vector<std::string> expected{"scene", "probe shadow", "echographic image", "b-mode", "image panel", "image cue", "ui"};
    EXPECT_EQ(r.frame()->pass_names(), expected);
    r.run();
    ASSERT_NE(ui, nullptr);
    EXPECT_EQ(ui->recorded, 2);  // a frame each step
    EXPECT_EQ(ui->set_up, 2);    // each given the step's view before it
    EXPECT_NEAR(ui->last_time_s, r.session().view().time_s, 1e-12);
}

TEST(ImageCue, OffTheVolumeNoContactOrNone)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    const echo::ImagePlane plane;
    echo::EchoFrame f;
    f.face = leg.probe_rest_pose(0.5f, 0.5f);
    EXPECT_EQ(runner::image_cue(f, plane, *v.grey), runner::ImageCue::no_contact);  // nothing pressed
    f.columns.assign(plane.columns, echo::ColumnProfile{});
    EXPECT_EQ(runner::image_cue(f, plane, *v.grey), runner::ImageCue::none);
    f.face.position += glm::vec3(f.face.axis_z()) * 30.0f;  // slid 30 mm along the thigh, off the test volume (+-4 mm)
    EXPECT_EQ(runner::image_cue(f, plane, *v.grey), runner::ImageCue::outside_region);
    EXPECT_STREQ(runner::cue_text(runner::ImageCue::no_contact).headline, "NO CONTACT");
    EXPECT_STREQ(runner::cue_text(runner::ImageCue::outside_region).headline, "OUTSIDE THE MODELLED REGION");
}

// How many of the frame's pixels inside `rect` are the banner's amber (255, 190, 40).
int amber_pixels(const io::RgbaImage& image, const render::TargetRect& rect)
{
    const VkRect2D px = render::target_pixels(rect, {image.width, image.height});
    int n = 0;
    for (std::uint32_t y = std::uint32_t(px.offset.y); y < std::uint32_t(px.offset.y) + px.extent.height; ++y)
        for (std::uint32_t x = std::uint32_t(px.offset.x); x < std::uint32_t(px.offset.x) + px.extent.width; ++x) {
            const std::uint8_t* p = image.at(x, y);
            n += p[0] > 200 && p[1] > 140 && p[1] < 230 && p[2] < 90 ? 1 : 0;
        }
    return n;
}

// Keeps the last frame's pixels.
struct KeepFrame final : runner::Observer {
    io::RgbaImage last;
    void on_step(runner::StepContext& step) override { step.want_frame(true); }
    void on_frame(const runner::FrameContext& f) override
    {
        if (f.pixels) last = *f.pixels;
    }
};

// The small volume's exam at 480 x 270 for `seconds`, the probe placed by `place` (at its rest
// pose pressed `press_mm`), every frame kept by `keep`.
runner::ExamOptions kept_exam(const TestVolumes& v, double seconds, const Pose& rest, double press_mm, std::shared_ptr<PlaceProbe>& place,
                              std::shared_ptr<KeepFrame>& keep)
{
    runner::ExamOptions o = small_exam(v);
    o.extent = {480, 270};
    o.duration_s = seconds;
    place = std::make_shared<PlaceProbe>();
    place->rest = rest;
    place->press_mm = press_mm;
    o.input = place;
    keep = std::make_shared<KeepFrame>();
    o.observers.push_back(keep);
    return o;
}

TEST(Runner, ThePanelSaysNoContactOffTheSkinAndNothingWhilePressing)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    std::shared_ptr<PlaceProbe> place;
    std::shared_ptr<KeepFrame> keep;
    const Pose rest = leg.probe_rest_pose(0.5f, 0.5f);
    runner::ExamOptions o = kept_exam(v, 1.0, pressed_along_beam(rest, -8.0), 0.0, place, keep);  // 8 mm above the skin
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    // ECHOSIM_RUNNER_FRAMES=DIR keeps the two frames to look at
    const char* keep_dir = std::getenv("ECHOSIM_RUNNER_FRAMES");
    {
        runner::Runner r(runner::exam_config(std::move(o)));
        messages = r.validation_counter();
        for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.step());
        EXPECT_EQ(r.frame()->cue(), runner::ImageCue::no_contact);
        const render::TargetRect panel = runner::echo_panel_rect({480, 270}, r.session().image_plane());
        const io::RgbaImage lifted = keep->last;
        EXPECT_GT(amber_pixels(lifted, panel), 200);  // the banner's frame and headline
        if (keep_dir) io::write_png(std::filesystem::path(keep_dir) / "h6_no_contact.png", lifted);

        place->rest = rest;
        place->press_mm = 8.0;
        for (int i = 0; i < 30; ++i) ASSERT_TRUE(r.step());
        EXPECT_EQ(r.frame()->cue(), runner::ImageCue::none);
        EXPECT_GT(r.session().view().probe_force_N, 0.5);
        EXPECT_EQ(amber_pixels(keep->last, panel), 0);  // the echo image alone
        if (keep_dir) io::write_png(std::filesystem::path(keep_dir) / "h6_pressing.png", keep->last);

        // slid along the thigh past the volume (the test volume is 8 mm thick): the other cue
        place->rest = leg.probe_rest_pose(0.6f, 0.5f);
        for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.step());
        EXPECT_EQ(r.frame()->cue(), runner::ImageCue::outside_region);
        EXPECT_GT(amber_pixels(keep->last, panel), 200);
        if (keep_dir) io::write_png(std::filesystem::path(keep_dir) / "h6_outside.png", keep->last);
    }
    EXPECT_EQ(messages->load(), 0u);
}

// A runner whose volume stands in for one being made (`echosim run`'s first window) says so on the
// image whatever the probe does: pressing on the skin, the cue stays IMAGES BEING MADE.
TEST(Runner, AStandInVolumeSaysTheImagesAreBeingMade)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    std::shared_ptr<PlaceProbe> place;
    std::shared_ptr<KeepFrame> keep;
    runner::ExamOptions o = kept_exam(v, 1.0, leg.probe_rest_pose(0.5f, 0.5f), 8.0, place, keep);
    runner::RunnerConfig config = runner::exam_config(std::move(o));
    config.volume_pending = true;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner r(std::move(config));
        messages = r.validation_counter();
        for (int i = 0; i < 30; ++i) ASSERT_TRUE(r.step());
        EXPECT_GT(r.session().view().probe_force_N, 0.5);  // pressing: no other cue would show
        EXPECT_EQ(r.frame()->cue(), runner::ImageCue::volume_pending);
        const render::TargetRect panel = runner::echo_panel_rect({480, 270}, r.session().image_plane());
        EXPECT_GT(amber_pixels(keep->last, panel), 200);
        if (const char* keep_dir = std::getenv("ECHOSIM_RUNNER_FRAMES"))  // to look at
            io::write_png(std::filesystem::path(keep_dir) / "h6_volume_pending.png", keep->last);
    }
    EXPECT_EQ(messages->load(), 0u);
    EXPECT_STREQ(runner::cue_text(runner::ImageCue::volume_pending).headline, "IMAGES BEING MADE");
}

// The scanner's knobs: gain and focus step and stop at their ends; a focus is kept inside the image.
TEST(ScannerControls, GainAndFocusStepWithinTheirRanges)
{
    echo::ScannerSettings s;
    s.gain_db = 0;
    s.focus_mm = 20;
    echo::ScannerSettings t = runner::adjusted(s, {.gain_steps = 2, .focus_steps = -1}, 50.0);
    EXPECT_DOUBLE_EQ(t.gain_db, 2 * runner::kGainStepDb);
    EXPECT_DOUBLE_EQ(t.focus_mm, 20 - runner::kFocusStepMm);
    EXPECT_EQ(t.dynamic_range_db, s.dynamic_range_db);
    t = runner::adjusted(s, {.gain_steps = 100, .focus_steps = 100}, 50.0);
    EXPECT_DOUBLE_EQ(t.gain_db, runner::kMaxGainDb);
    EXPECT_DOUBLE_EQ(t.focus_mm, 50.0 - runner::kFocusMarginMm);
    t = runner::adjusted(s, {.gain_steps = -100, .focus_steps = -100}, 50.0);
    EXPECT_DOUBLE_EQ(t.gain_db, -runner::kMaxGainDb);
    EXPECT_DOUBLE_EQ(t.focus_mm, runner::kFocusMarginMm);
    // the depth: a centimetre a step, kept within the range
    EXPECT_DOUBLE_EQ(runner::adjusted_depth(50, 1, 30, 70), 60);
    EXPECT_DOUBLE_EQ(runner::adjusted_depth(50, -2, 30, 70), 30);
    EXPECT_DOUBLE_EQ(runner::adjusted_depth(50, 9, 30, 70), 70);
    EXPECT_DOUBLE_EQ(runner::adjusted_depth(50, -9, 30, 70), 30);
    // the focus follows a shallower image into it
    t = runner::adjusted({.focus_mm = 40}, {}, 30.0);
    EXPECT_DOUBLE_EQ(t.focus_mm, 30.0 - runner::kFocusMarginMm);
}

// Freeze: the panel keeps the frozen image while the probe presses on (the scene shows the press),
// and follows the probe again once unfrozen; gain changes what the panel shows.
TEST(Runner, AFrozenImageStaysWhileTheProbeMovesOn)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    std::shared_ptr<PlaceProbe> place;
    std::shared_ptr<KeepFrame> keep;
    runner::ExamOptions o = kept_exam(v, 2.0, leg.probe_rest_pose(0.5f, 0.5f), 2.0, place, keep);
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner r(runner::exam_config(std::move(o)));
        messages = r.validation_counter();
        const render::TargetRect panel_rect = runner::echo_panel_rect({480, 270}, r.session().image_plane());
        const VkRect2D panel = render::target_pixels(panel_rect, {480, 270});
        const auto panel_of = [&](const io::RgbaImage& f) {
            std::vector<std::uint8_t> bytes;
            for (std::uint32_t y = std::uint32_t(panel.offset.y); y < std::uint32_t(panel.offset.y) + panel.extent.height; ++y)
                for (std::uint32_t x = std::uint32_t(panel.offset.x); x < std::uint32_t(panel.offset.x) + panel.extent.width; ++x)
                    bytes.insert(bytes.end(), f.at(x, y), f.at(x, y) + 3);
            return bytes;
        };
        const auto scene_of = [&](const io::RgbaImage& f) {
            std::vector<std::uint8_t> bytes;
            for (std::uint32_t y = 0; y < f.height; ++y) bytes.insert(bytes.end(), f.at(0, y), f.at(0, y) + 4 * std::size_t(panel.offset.x));
            return bytes;
        };
        for (int i = 0; i < 10; ++i) ASSERT_TRUE(r.step());
        runner::apply(*r.frame(), {.toggle_freeze = true});
        EXPECT_NE(runner::scanner_status(*r.frame()).find("FROZEN"), std::string::npos);
        EXPECT_EQ(runner::scanner_status(*r.frame()).rfind("interpolative image, ", 0), 0u) << runner::scanner_status(*r.frame());
        ASSERT_TRUE(r.step());
        const io::RgbaImage frozen = keep->last;
        place->press_mm = 10.0;  // pressed 8 mm further
        for (int i = 0; i < 25; ++i) ASSERT_TRUE(r.step());
        EXPECT_EQ(panel_of(keep->last), panel_of(frozen)) << "the frozen image stays";
        EXPECT_NE(scene_of(keep->last), scene_of(frozen)) << "the scene shows the press going on";
        runner::apply(*r.frame(), {.toggle_freeze = true});
        ASSERT_TRUE(r.step());
        ASSERT_TRUE(r.step());  // the slot drawn before the unfreeze is shown no more
        const io::RgbaImage live = keep->last;
        EXPECT_NE(panel_of(live), panel_of(frozen)) << "unfrozen, the image follows the press";
        runner::apply(*r.frame(), {.gain_steps = 5});
        ASSERT_TRUE(r.step());
        ASSERT_TRUE(r.step());
        const std::vector<std::uint8_t> brighter = panel_of(keep->last), before = panel_of(live);
        long sum_brighter = 0, sum_before = 0;
        for (std::size_t i = 0; i < before.size(); ++i) sum_brighter += brighter[i], sum_before += before[i];
        EXPECT_GT(sum_brighter, sum_before) << "10 dB more gain: a brighter image";

        // depth: not while frozen (the frozen image keeps its scale, and a caliper on it stays
        // true); live, 2 cm deeper, the panel narrower for the same height, the status says so;
        // then as shallow as it goes, the focus (40 mm) brought into the 30 mm image
        runner::apply(*r.frame(), {.focus_steps = 8, .toggle_freeze = true});
        runner::apply(*r.frame(), {.depth_steps = 2});
        EXPECT_EQ(r.frame()->echo_image().plane().depth_mm, kLinearProbe.image_depth_mm);
        runner::apply(*r.frame(), {.toggle_freeze = true});
        runner::apply(*r.frame(), {.depth_steps = 2});
        EXPECT_EQ(r.frame()->echo_image().plane().depth_mm, kLinearProbe.image_depth_mm + 2 * runner::kDepthStepMm);
        EXPECT_NE(runner::scanner_status(*r.frame()).find("depth 7.0 cm"), std::string::npos) << runner::scanner_status(*r.frame());
        ASSERT_TRUE(r.step());
        ASSERT_TRUE(r.step());
        const render::TargetRect deeper_rect = runner::echo_panel_rect({480, 270}, r.frame()->echo_image().plane());
        EXPECT_LT(deeper_rect.width, panel_rect.width);
        EXPECT_NEAR(deeper_rect.width / panel_rect.width, 50.0 / 70.0, 1e-5);
        EXPECT_DOUBLE_EQ(r.frame()->echo_image().scanner().focus_mm, 40.0);
        runner::apply(*r.frame(), {.depth_steps = -9});
        EXPECT_EQ(r.frame()->echo_image().plane().depth_mm, kLinearProbe.image_depth_min_mm);
        EXPECT_DOUBLE_EQ(r.frame()->echo_image().scanner().focus_mm, kLinearProbe.image_depth_min_mm - runner::kFocusMarginMm);
        ASSERT_TRUE(r.step());
    }
    EXPECT_EQ(messages->load(), 0u);
}

// A tube around a line: `sides` vertices a point, each at the point's radius from it, and two
// triangles a side between consecutive points.
TEST(GuidePass, TubesHaveTheirRadiiAroundTheLine)
{
    runner::GuideLine line{{{0, 0, 0}, {0, 0, -10}, {5, 0, -20}}, {2.0f, 3.0f, 1.0f}, {}};
    const runner::TubeMesh m = runner::tube_mesh(line, 6);
    ASSERT_EQ(m.positions.size(), 18u);
    EXPECT_EQ(m.indices.size(), 2u * 6u * 6u);
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(glm::distance(m.positions[6 * i + k], line.centre[i]), line.radius_mm[i], 1e-4f);
    for (std::uint32_t idx : m.indices) EXPECT_LT(idx, 18u);
    EXPECT_TRUE(runner::tube_mesh({{{0, 0, 0}}, {1.0f}, {}}).indices.empty());
}

// The practice guides, shown: the leg's side of the frame gains the vessels' blue and red where the
// course runs and the image plane's amber at the probe; the image panel is untouched; hidden, the
// frame is the frame without them, byte for byte.
TEST(GuidePass, ShownTheVesselsAndThePlaneShowThroughTheLeg)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    const std::vector<runner::GuideLine> course = runner::course_guides(leg, echo::Anatomy{});
    ASSERT_GE(course.size(), 2u);
    EXPECT_GT(course[0].centre.size(), 100u) << "the deep vein sampled every 5 mm over 51.5 cm";
    EXPECT_NEAR(course[0].centre.front().z, 15.0f, 5.0f) << "from above the ligament";
    EXPECT_LT(course[0].centre.back().z, -450.0f) << "to the trifurcation";
    auto shown = std::make_shared<runner::GuideSwitch>();
    runner::ExamOptions o = small_exam(v);
    o.extent = {480, 270};
    o.duration_s = 1.0;
    auto place = std::make_shared<PlaceProbe>();
    place->rest = leg.probe_rest_pose(0.5f, 0.5f);
    o.input = place;
    auto keep = std::make_shared<KeepFrame>();
    o.observers.push_back(keep);
    runner::RunnerConfig c = runner::exam_config(std::move(o));
    c.passes.push_back(runner::guide_pass_factory(course, shown));
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner r(std::move(c));
        messages = r.validation_counter();
        ASSERT_TRUE(r.step());
        ASSERT_TRUE(r.step());
        const io::RgbaImage without = keep->last;
        shown->shown = true;
        ASSERT_TRUE(r.step());
        const io::RgbaImage with = keep->last;
        const render::TargetRect panel = runner::echo_panel_rect({480, 270}, r.session().image_plane());
        const std::uint32_t panel_x = render::target_pixels(panel, {480, 270}).offset.x;
        int bluer = 0, redder = 0, changed_in_panel = 0;
        for (std::uint32_t y = 0; y < 270; ++y)
            for (std::uint32_t x = 0; x < 480; ++x) {
                const std::uint8_t *a = without.at(x, y), *b = with.at(x, y);
                if (x >= panel_x) {
                    changed_in_panel += std::equal(a, a + 3, b) ? 0 : 1;
                    continue;
                }
                bluer += b[2] > a[2] + 20 && b[0] < a[0] ? 1 : 0;
                redder += b[0] > a[0] + 10 && b[2] < a[2] ? 1 : 0;
            }
        EXPECT_GT(bluer, 200) << "the veins";
        EXPECT_GT(redder, 100) << "the artery and the plane";
        EXPECT_EQ(changed_in_panel, 0);
        if (const char* dir = std::getenv("ECHOSIM_RUNNER_FRAMES")) io::write_png(std::filesystem::path(dir) / "guides.png", with);
        shown->shown = false;
        ASSERT_TRUE(r.step());
        EXPECT_EQ(keep->last.pixels, without.pixels);
    }
    EXPECT_EQ(messages->load(), 0u);
}

TEST(Runner, TwoExamRunsWriteTheSameFrameBytes)
{
    const TestVolumes v = small_volume();
    const scene::LegModel leg;
    app::SlideScript script;  // down onto the thigh, pressing 6 mm in, sliding across it, lifting
    script.approach_s = 0.15;
    script.hold_s = 0.05;
    script.slide_s = 0.2;
    script.v_from = 0.45;
    script.v_to = 0.55;
    const app::SlideTrajectory slide = app::make_slide_trajectory(leg, script);
    const std::filesystem::path base = std::filesystem::path(testing::TempDir()) / "runner_repeat";
    std::filesystem::remove_all(base);
    std::vector<std::vector<std::string>> runs;
    for (int run = 0; run < 2; ++run) {
        runner::ExamOptions o = small_exam(v);
        o.trajectory = slide.trajectory;
        o.frames_per_s = 10;
        o.frames_dir = base / std::to_string(run);
        runner::Runner r(runner::exam_config(std::move(o)));
        r.run();
        EXPECT_EQ(r.validation_counter()->load(), 0u);
        std::vector<std::string> bytes;
        for (int k = 0;; ++k) {
            const std::filesystem::path f = base / std::to_string(run) / runner::FrameRecorder::file_name(k);
            if (!std::filesystem::exists(f)) break;
            bytes.push_back(file_bytes(f));
        }
        runs.push_back(std::move(bytes));
    }
    ASSERT_GE(runs[0].size(), 6u);  // 0.6 s at 10 frames a simulated second
    ASSERT_EQ(runs[0].size(), runs[1].size());
    for (std::size_t k = 0; k < runs[0].size(); ++k) EXPECT_TRUE(runs[0][k] == runs[1][k]) << "frame " << k << " differs";
    EXPECT_NE(runs[0].front(), runs[0][runs[0].size() / 2]);  // the probe moved: the frames are not all one
    std::filesystem::remove_all(base);
}

}  // namespace
}  // namespace echosim

// The trainer in the runner (issue 32): one observer and the UI pass. Each step the driver hands
// the session's view to the trainer's scorer (as `echosim exam`'s ScorerObserver does), then the
// step's input (fed by the runner's Input: the window's callbacks or a test's script) to the
// trainer's shortcut keys, then the idle clock; the UI pass gets the same input and draws the
// trainer's screens (trainer/trainer_screens.hpp), where a button acts as its key does. A call
// made by key or button lands after the step's observation, at the step's time: the moment a
// scripted exam's call lands at, so a lesson driven by keys is scored as the same script headless.
//
// The runner's volumes are one case's: a lesson started on another case asks the driver's owner to
// rebuild the runner for it (case_wanted(), should_stop()); the trainer outlives runners.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "echo/echo_frame.hpp"
#include "io/png.hpp"
#include "runner/runner.hpp"
#include "trainer/trainer.hpp"
#include "trainer/station_sheet_pass.hpp"
#include "trainer/trainer_screens.hpp"
#include "ui/ui_pass.hpp"

namespace echosim::trainer {

struct DriverOptions {
    ui::UiOptions ui;
    std::function<float()> ui_scale;  // when set: the UI's scale, asked when the pass is made (the window open)
    // with Drawing::on_request (a lock-step run), a frame every this many steps besides the steps
    // with input (0: only those); with Drawing::every_step every step draws anyway
    int frame_every_steps = 6;
    std::string loaded_case;  // the id of the case whose volumes the runner holds
    std::shared_ptr<const io::Volume> volume, labels;  // for the report's station images
    echo::PatientCase patient;
};

// Where the probe (the camera's target) should appear in the leg's view, in normalised device
// coordinates: in the middle of the view's part right of the exam screen's panel (at 1280 x 720 the
// panel covers more than half the view, the probe at its centre hidden under it); the centre when
// there is no panel or too little of the view is left beside it.
glm::vec2 probe_on_screen(const std::optional<ScreenState::Rect>& panel, VkExtent2D extent, const echo::ImagePlane& plane);

class TrainerDriver final : public runner::Observer {
public:
    TrainerDriver(std::shared_ptr<Trainer> trainer, DriverOptions options);

    // The runner configuration's passes, in this order (PassPlace::overlay): the UI pass, then the
    // report screen's station images over it (trainer/station_sheet_pass.hpp).
    std::vector<runner::PassFactory> passes();
    ui::UiPass* ui() { return ui_; }
    Trainer& trainer() { return *trainer_; }

    // The step's input (the runner's Input calls it at its poll).
    void feed(const ui::UiInput& input);

    // The screens' state: where each button was drawn last (a test clicks them there).
    const ScreenState& screens() const { return screens_; }
    bool quit_requested() const { return quit_; }
    // The case a started lesson needs when the runner holds another's volumes.
    const std::optional<std::string>& case_wanted() const { return case_wanted_; }
    // The next frame read back (offscreen) into `sink`, once.
    void capture(std::function<void(const io::RgbaImage&)> sink) { capture_ = std::move(sink); }
    // Asks the driver's owner for a runner holding `case_id`'s volumes with no lesson started (the
    // run's first runner holds no case's while its volume is made: app/trainer_window.hpp).
    void want_case(const std::string& case_id) { case_wanted_ = case_id; }
    // Every case's lesson runs on the volumes held (a user's own volume): none asks for a runner anew.
    void accept_any_case() { any_case_ = true; }
    // The caliper on the frozen image during a lesson (trainer/caliper.hpp): a left click on the
    // image places its points (drawn by the UI pass); the image unfrozen, it is cleared.
    const Caliper& caliper() const { return caliper_; }
    // Whether the mouse was over the frozen image at the last frame: its left button is the
    // caliper's then, not the view's orbit.
    bool caliper_hovered() const { return caliper_hovered_; }

    void on_attach(runner::Runner& runner) override;
    bool should_stop() override { return quit_ || case_wanted_.has_value(); }
    void on_step(runner::StepContext& step) override;
    void on_frame(const runner::FrameContext& frame) override;

private:
    void act(Action a);
    // The caliper's clicks and drawing, in the UI pass's draw callback.
    void update_caliper(VkExtent2D extent);
    // The displayed image's plane (its depth the scanner's control's), the session's without a frame.
    echo::ImagePlane image_plane();

    std::shared_ptr<Trainer> trainer_;
    DriverOptions options_;
    runner::PassFactory ui_pass();
    ui::UiPass* ui_ = nullptr;
    StationSheetPass* sheet_ = nullptr;
    runner::Runner* runner_ = nullptr;
    // the trainer's report maker: the stations' images made with `imaging`
    void make_reports(echo::Imaging imaging);
    std::vector<ui::UiInput> pending_;
    float last_mouse_x_ = -1, last_mouse_y_ = -1;
    bool quit_ = false;
    std::optional<std::string> case_wanted_;
    std::function<void(const io::RgbaImage&)> capture_;
    bool any_case_ = false;
    Caliper caliper_;
    bool caliper_hovered_ = false;
    ScreenState screens_;
    int input_frames_ = 0;  // frames still wanted after an input (ImGui sees a release a frame later)
};

}  // namespace echosim::trainer

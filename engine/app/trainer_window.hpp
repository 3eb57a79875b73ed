// The trainer in `echosim run` (issue 32): what the window's run adds for it, kept here so the run
// (app/cmd_run.cpp) only calls in at four places: the volumes of the lesson's case, the runner's
// configuration (the UI pass, the trainer's driver, the kiosk's fullscreen window), the input's
// filter each step, and whether to run again for another case.
//
//   - the cases: the shipped ones (assets/cases); `--case ID` (or random) pre-selects one; their
//     volumes are the exams' (app/exam_volume.hpp, made once and cached), a runner holds one case's,
//     so a lesson started on another case ends the runner and the run starts a new one for it in
//     the same window (runner::RunnerConfig::shared_window);
//   - a case's volume not cached yet is made on a thread of its own (app/volume_preparer.hpp)
//     while the window runs: the chosen case's first (the start screen says how far it is, and a
//     start asked for begins the lesson once it is ready), then, in the kiosk, every other case's;
//     the first runner, when the chosen case's volume is not cached, holds no case's (an empty
//     volume: the image says IMAGES BEING MADE) and gives way to one that holds it once made;
//   - the UI's input from the window (UiWindowInput): GLFW polled for the mouse (sticky buttons: a
//     click between two frames is kept) and the keys, typed characters from GLFW's character
//     callback; fed to the trainer's driver;
//   - while a text field has the keyboard and keys are down, the run's own keys (the probe, the scanner, the view,
//     fullscreen, Esc) stand aside; while the mouse is over the UI, it does not orbit the camera;
//   - the kiosk (`--kiosk`): fullscreen at the display's resolution (gpu::Window caps it at
//     3840x2160), the UI scaled from the monitor's content scale and at least to the display's height
//     over 1080 (read standing), Esc and F11 do nothing (Ctrl+Alt+Q quits), `--idle-timeout S`
//     (default 120) scores and stores an idle lesson and shows the start screen again.
// Threads: the main thread (GLFW's rule).
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/run_input.hpp"
#include "app/terminal_progress.hpp"
#include "app/volume_preparer.hpp"
#include "app/volume_source.hpp"
#include "gpu/context.hpp"
#include "runner/runner.hpp"
#include "trainer/trainer_driver.hpp"
#include "ui/ui_input.hpp"

struct GLFWwindow;

namespace echosim::app {

// The UI's input from a GLFW window (above). One at a time per process: GLFW's character callback
// reaches it through a pointer kept for the window's lifetime (main thread only).
class UiWindowInput {
public:
    explicit UiWindowInput(GLFWwindow* window);
    ~UiWindowInput();
    UiWindowInput(const UiWindowInput&) = delete;
    UiWindowInput& operator=(const UiWindowInput&) = delete;
    ui::UiInput poll();

private:
    GLFWwindow* window_;
    std::u32string chars_;
    bool down_[int(ui::Key::count)] = {};
    static void on_char(GLFWwindow* window, unsigned int c);
};

class TrainerWindow {
public:
    // Reads the cases and opens nothing yet; throws naming what is wrong (an unknown --case).
    explicit TrainerWindow(const RunArgs& args);

    trainer::Trainer& trainer() { return *trainer_; }
    // The case the next runner needs: the lesson's when one waits for its case, else the one chosen.
    const exam::Scenario& case_to_load() const;
    VolumePair load_volumes(const gpu::ContextOptions& gpu, TerminalProgress& progress);
    // The runner's configuration for the case loaded: the patient, the UI pass and the driver, the
    // kiosk's window.
    void configure(runner::RunnerConfig& config);
    // The runner made: the window's UI input, and a lesson that waited for its case started anew.
    void attach(runner::Runner& runner);
    // Each step, before the run's own input is read: the window's keys and mouse for the UI. First,
    // because the keys are sticky (a tap between two polls reads as pressed once): the UI's
    // shortcuts (C, N, I, Ctrl+Alt+Q, F-keys) must see a tap before the probe's keys (Q/E, W/S ...)
    // are read and consume it.
    void read_ui();
    // Each step, the run's own input read: a name typed moves no probe; the kiosk's limits.
    void filter(runner::Runner& runner, RunInput& in);
    // The runner holds no case's volumes yet: the chosen one's are being made.
    bool placeholder() const { return placeholder_; }
    // After detach: a lesson started waits for the next runner (its case's).
    bool lesson_waits() const { return resume_; }
    // After a runner ended: whether the run goes on with another case's runner.
    bool again() const { return driver_ && driver_->case_wanted().has_value(); }
    // The runner gone (its window with it); a lesson under way when the run ends is scored and
    // stored as it stands.
    void detach();

private:
    RunArgs args_;
    std::shared_ptr<trainer::Trainer> trainer_;
    std::shared_ptr<trainer::TrainerDriver> driver_;
    std::unique_ptr<UiWindowInput> input_;
    ui::UiInput typed_;  // the UI input read this step (read_ui), for filter
    std::string loaded_;          // the case whose volumes the runner holds
    VolumePair volumes_;
    bool resume_ = false;         // a lesson waits for its case's runner
    bool placeholder_ = false;    // the runner holds the empty volume (above)
    std::unique_ptr<VolumePreparer> preparer_;  // none with the user's own volume
    trainer::Screen logged_ = trainer::Screen::start;  // the screen the log last said
    int logged_made_ = -1;                            // how many cases' images the log last said were made (kiosk)
    static constexpr double kMakingFrameRate = 10;    // the start screen's while a volume is made
    std::chrono::steady_clock::time_point last_ui_;   // the last read_ui's end
    void log_screen();
    void log_made();
    // what the start screen says of a case's volume (the preparer's status), and of the other
    // cases' a kiosk makes behind it
    trainer::CaseReadiness readiness(const exam::Scenario& c) const;
    std::string made_line() const;
};

}  // namespace echosim::app

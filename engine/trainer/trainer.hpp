// The trainer a trainee sits at (DESIGN.md §1, "trainer"; issue 32): the lesson's state, apart
// from any screen or GPU, so tests drive it without one. Three screens:
//
//   start ──(Start: Enter)──▶ exam ──(Finish: End; or the idle timeout)──▶ report ──(Enter)──▶ start
//     │                        │                                   ▲
//     └ name, lesson, case,    └ the scorer watches every step;    └ the report's files written,
//       difficulty               calls C / N; guidance to the        the session stored in the
//                                next station; the force gauge       records; earlier sessions listed
//
// A start asked for while the chosen case's images are still being made (the run's first minute on
// a new machine, a kiosk's other cases) waits on the start screen and begins once they are ready
// (set_readiness, request_start).
//
// The idle timeout (no input, the probe still, for TrainerOptions::idle_timeout_s of session time):
// during an exam the session is scored and stored as it stands, and the trainer returns to the start
// screen (a kiosk left by its trainee is ready for the next); on the report screen it returns too.
//
// The trainer does not own the runner: a driver (trainer/trainer_driver.hpp) feeds it each step's
// sample, the UI's actions and the shortcut keys, and gives it the way to image and write a report
// (the case's volumes are the driver's). Threads: the runner's driver thread.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exam/exam_report.hpp"
#include "exam/records.hpp"
#include "exam/scenario.hpp"
#include "exam/scorer.hpp"
#include "trainer/guidance.hpp"
#include "trainer/lesson.hpp"
#include "ui/ui_input.hpp"

namespace echosim::trainer {

enum class Screen { start, exam, report };
const char* screen_name(Screen s);  // "start", "exam", "report"

struct TrainerOptions {
    std::vector<std::filesystem::path> cases;  // to choose from (exam::shipped_cases()); at least one
    std::filesystem::path records;             // the trainee records database ("": none kept)
    std::filesystem::path reports;             // each session's report in a folder of its own under it
    double idle_timeout_s = 120;               // 0: never
    bool kiosk = false;
    std::uint64_t seed = 1;                    // the random case's draws
    bool stamp_time = true;                    // the report's started_utc (false: repeatable runs)
};

// The start screen's choices.
struct StartForm {
    std::string trainee;
    exam::Protocol lesson = exam::Protocol::extended;
    int case_index = 0;  // into cases(); -1: random
    Difficulty difficulty = Difficulty::beginner;
};

// What the trainer asks the driver to do after an input (the driver owns the runner).
enum class Action { none, started, finished, quit };

// Whether a case's volumes are ready for a lesson (its images: made once, then cached), and if not,
// the line the start screen shows beside Start ("This case's images are being made, once (then
// kept): imaging the course (1060 frames).") and how far the making is (its progress bar). A ready
// case's line, if any, says how far the other cases' are (a kiosk makes them all), shown quieter.
struct CaseReadiness {
    bool ready = true;
    std::string line;
    double done = -1;  // how far the making is, 0..1 (< 0: not being made now)
};

class Trainer {
public:
    // Reads every case (throws exam::ScenarioError naming a bad one).
    explicit Trainer(TrainerOptions options);

    Screen screen() const { return screen_; }
    StartForm& form() { return form_; }
    const StartForm& form() const { return form_; }
    const std::vector<exam::Scenario>& cases() const { return cases_; }
    const TrainerOptions& options() const { return options_; }
    // Pre-selects a case by its id (run --case); false when none has it.
    bool select_case(const std::string& id);

    // --- start screen
    // The case the form chooses now (random: the one the next start draws).
    const exam::Scenario& chosen_case() const;
    // Starts the lesson at `time_s` of the session: the case (a random one drawn), the lesson's
    // stations, their truth from the case's phantom, a new scorer. Throws std::invalid_argument
    // when the case cannot be examined by the lesson's protocol.
    void start(double time_s);
    // Start asked for (Enter, the button): the lesson starts now when the chosen case is ready
    // (Action::started), else once it is (tick returns Action::started then; the case chosen then).
    Action request_start(double time_s);
    // How the trainer learns whether a case is ready (the run's volume preparer); none: all are.
    void set_readiness(std::function<CaseReadiness(const exam::Scenario&)> readiness) { readiness_ = std::move(readiness); }
    CaseReadiness readiness(const exam::Scenario& c) const { return readiness_ ? readiness_(c) : CaseReadiness{}; }
    // A start asked for waits for the chosen case's images.
    bool start_waiting() const { return start_waiting_; }
    // Starts the same lesson again at `time_s`, a new scorer (the driver rebuilt the runner for the
    // lesson's case: a new session, its clock from 0).
    void restart(double time_s);

    // --- exam screen
    const exam::Scenario& lesson() const { return lesson_; }  // the case with the lesson's stations
    const exam::Scorer& scorer() const { return *scorer_; }
    void observe(const exam::ExamSample& sample);
    void call(double time_s, exam::Call c);
    double started_s() const { return started_s_; }
    // A station is done once reached, pressed into the adequate band and called.
    bool station_done(std::size_t i) const;
    // Wrong so far: a wrong call, excessive force, an oblique plane, the wrong vessel pressed.
    bool station_wrong(std::size_t i) const;
    // The station to go to next: the first not done, in the protocol's order (none: all done).
    std::optional<std::size_t> target() const;
    const exam::ExamSample& last_sample() const { return last_; }

    // How the report is made from the scorer (images and files: the driver's volumes) into `out`.
    using ReportMaker = std::function<exam::ExamReport(const exam::Scorer& scorer, const std::filesystem::path& out, const std::string& trainee)>;
    void set_report_maker(ReportMaker make) { make_report_ = std::move(make); }
    // Ends the exam: the report made and written, the session stored in the records (when kept),
    // the earlier sessions read; then the report screen, or the start screen (`to_start`: the idle
    // timeout). Errors storing are kept in last_error(), never thrown (the trainee's report stays).
    void finish(bool to_start = false);

    // --- report screen
    const exam::ExamReport& report() const { return report_; }
    const std::filesystem::path& report_dir() const { return report_dir_; }
    std::int64_t stored_id() const { return stored_id_; }  // 0: not stored
    const std::vector<exam::SessionRecord>& earlier() const { return earlier_; }
    void new_lesson();  // back to the start screen, the form kept
    // Whether the report screen shows the stations' images at their deepest press in place of
    // its station table (the I key, or its button); a new lesson's report opens on the table.
    bool report_images_shown() const { return report_images_; }
    void toggle_report_images() { report_images_ = !report_images_; }
    const std::string& last_error() const { return error_; }
    const std::string& message() const { return message_; }  // a line for the start screen

    // --- input
    // The shortcut keys of the screen (below); `text_active`: a text field has the keyboard, so
    // letters are typed, not shortcuts. Returns what the driver must do.
    //   start:  Enter start; F1 two-point, F2 three-point, F3 extended; F4 / F5 previous / next case,
    //           F6 random case; F7 difficulty (beginner, intermediate, expert in turn)
    //   exam:   C compressible, N not compressible, End finish, H guidance on or off
    //   report: Enter a new lesson, I the stations' images or their table
    //   any:    Ctrl+Alt+Q quit (the instructor's); Esc quits unless in the kiosk
    Action keys(const ui::UiInput& in, double time_s, bool text_active);
    // Counts the input and the probe's motion as activity; applies the idle timeout at `time_s`;
    // starts a lesson that waited for its case once the case is ready. Returns Action::finished
    // when it ended an exam, Action::started when it started one.
    Action tick(double time_s, bool active);
    bool guidance_on() const { return guidance_on_; }
    double idle_s(double time_s) const { return time_s - last_active_s_; }

    // The list the start screen names the lessons by.
    static constexpr exam::Protocol kLessons[3] = {exam::Protocol::two_point, exam::Protocol::three_point, exam::Protocol::extended};

private:
    TrainerOptions options_;
    std::vector<exam::Scenario> cases_;
    StartForm form_;
    Screen screen_ = Screen::start;
    std::uint64_t draws_ = 0;        // random cases drawn so far
    int lessons_ = 0;                // lessons started (the report folders' numbers)
    exam::Scenario lesson_;
    std::unique_ptr<exam::Scorer> scorer_;
    double started_s_ = 0;
    exam::ExamSample last_;
    ReportMaker make_report_;
    exam::ExamReport report_;
    std::filesystem::path report_dir_;
    std::int64_t stored_id_ = 0;
    std::vector<exam::SessionRecord> earlier_;
    std::string error_, message_;
    bool guidance_on_ = true;
    bool report_images_ = false;
    std::function<CaseReadiness(const exam::Scenario&)> readiness_;
    bool start_waiting_ = false;
    double last_active_s_ = 0;
    Pose last_pose_;
};

}  // namespace echosim::trainer

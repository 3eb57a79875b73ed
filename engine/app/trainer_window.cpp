#include "app/trainer_window.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include <GLFW/glfw3.h>

#include "app/exam_volume.hpp"
#include "app/terminal_progress.hpp"
#include "exam/records.hpp"
#include "exam/scenario.hpp"

namespace echosim::app {
namespace {

// the UI's input of the one window (main thread only; GLFW's character callback has no other way
// to it: the window's user pointer is WindowInput's)
UiWindowInput* g_char_target = nullptr;

// our keys as GLFW's (letters, digits and space are the same codes)
int glfw_key(ui::Key k)
{
    using ui::Key;
    switch (k) {
    case Key::tab: return GLFW_KEY_TAB;
    case Key::enter: return GLFW_KEY_ENTER;
    case Key::escape: return GLFW_KEY_ESCAPE;
    case Key::backspace: return GLFW_KEY_BACKSPACE;
    case Key::del: return GLFW_KEY_DELETE;
    case Key::left: return GLFW_KEY_LEFT;
    case Key::right: return GLFW_KEY_RIGHT;
    case Key::up: return GLFW_KEY_UP;
    case Key::down: return GLFW_KEY_DOWN;
    case Key::home: return GLFW_KEY_HOME;
    case Key::end: return GLFW_KEY_END;
    case Key::page_up: return GLFW_KEY_PAGE_UP;
    case Key::page_down: return GLFW_KEY_PAGE_DOWN;
    default: break;
    }
    if (k >= Key::f1 && k <= Key::f12) return GLFW_KEY_F1 + (int(k) - int(Key::f1));
    const int c = int(k);
    if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == ' ') return c;
    return GLFW_KEY_UNKNOWN;
}

bool held(GLFWwindow* w, int a, int b) { return glfwGetKey(w, a) == GLFW_PRESS || glfwGetKey(w, b) == GLFW_PRESS; }

// the old `run --case` names, as the shipped exam cases that hold them
std::string case_id(const std::string& name)
{
    if (name == "dvt-acute") return "cfv-fv-acute";
    if (name == "dvt-chronic") return "fv-chronic";
    return name;
}

}  // namespace

std::string run_keys_help()
{
    return "Keys:\n"
           "  the trainer     start screen: type the name; F1 two-point, F2 three-point, F3 extended lesson; F4/F5 previous/next case,\n"
           "                  F6 random case; F7 difficulty; Enter starts. Exam: C compressible, N not compressible, H guidance on/off,\n"
           "                  End finishes. Report: I the stations' images or their table, Enter a new lesson. Ctrl+Alt+Q quits\n"
           "                  (the only way in --kiosk)\n"
           "  the probe       right-drag or arrows slide it, W/S or Shift+wheel press it in and out, Q/E and A/D tilt it,\n"
           "                  R levels it, T turns it (transverse/longitudinal)\n"
           "  the scanner     ] and [ depth (30 to 70 mm, a centimetre a step), + and - gain, Page Up and Page Down focus,\n"
           "                  Space freezes the image; on the frozen image two clicks measure the distance between them (the caliper)\n"
           "  the view        left-drag orbits, the wheel zooms, V (or Home) resets it; G shows the vessels and the image plane\n"
           "                  in the leg (practice guides); F11 (or F) fullscreen; Esc quits\n";
}

UiWindowInput::UiWindowInput(GLFWwindow* window) : window_(window)
{
    if (g_char_target) throw std::logic_error("the UI's window input: one at a time");
    g_char_target = this;
    glfwSetCharCallback(window_, &UiWindowInput::on_char);
    // a click or a key tapped between two polls still reads as pressed once: a frame on lavapipe at
    // 4K takes longer than a quick tap of F5 (a tap sent by xdotool, press and release at once, was
    // lost at 60 frames/s)
    glfwSetInputMode(window_, GLFW_STICKY_MOUSE_BUTTONS, GLFW_TRUE);
    glfwSetInputMode(window_, GLFW_STICKY_KEYS, GLFW_TRUE);
}

UiWindowInput::~UiWindowInput()
{
    glfwSetCharCallback(window_, nullptr);
    g_char_target = nullptr;
}

void UiWindowInput::on_char(GLFWwindow*, unsigned int c)
{
    if (g_char_target) g_char_target->chars_.push_back(char32_t(c));
}

ui::UiInput UiWindowInput::poll()
{
    ui::UiInput in;
    // the cursor in the framebuffer's pixels (a HiDPI window's differ from its screen coordinates)
    double x = 0, y = 0;
    glfwGetCursorPos(window_, &x, &y);
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(window_, &ww, &wh);
    glfwGetFramebufferSize(window_, &fw, &fh);
    if (ww > 0 && wh > 0 && glfwGetWindowAttrib(window_, GLFW_HOVERED)) {
        in.mouse_x = float(x * fw / ww);
        in.mouse_y = float(y * fh / wh);
    }
    in.mouse_down[0] = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    in.mouse_down[1] = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    in.mouse_down[2] = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    for (int k = 1; k < int(ui::Key::count); ++k) {
        const int code = glfw_key(ui::Key(k));
        if (code == GLFW_KEY_UNKNOWN) continue;
        const bool now = glfwGetKey(window_, code) == GLFW_PRESS;
        if (now) in.held.push_back(ui::Key(k));
        if (now && !down_[k]) in.pressed.push_back(ui::Key(k));
        down_[k] = now;
    }
    in.ctrl = held(window_, GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL);
    in.shift = held(window_, GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT);
    in.alt = held(window_, GLFW_KEY_LEFT_ALT, GLFW_KEY_RIGHT_ALT);
    in.chars = std::move(chars_);
    chars_.clear();
    return in;
}

TrainerWindow::TrainerWindow(const RunArgs& args) : args_(args)
{
    trainer::TrainerOptions o;
    o.cases = exam::shipped_cases();
    o.records = args.records.empty() ? exam::default_records_path() : args.records;
    o.reports = o.records.parent_path() / "reports";
    o.kiosk = args.kiosk;
    o.idle_timeout_s = args.kiosk ? args.idle_timeout_s : 0;  // a desk's run waits for its trainee
    o.seed = std::uint64_t(std::chrono::system_clock::now().time_since_epoch().count());
    trainer_ = std::make_shared<trainer::Trainer>(std::move(o));
    const std::string id = case_id(args.case_name);
    if (!trainer_->select_case(id)) {
        std::string ids;
        for (const exam::Scenario& c : trainer_->cases()) ids += (ids.empty() ? "" : ", ") + c.id;
        throw std::invalid_argument("--case " + args.case_name + ": not a shipped case (" + ids + ", or random)");
    }
}

const exam::Scenario& TrainerWindow::case_to_load() const
{
    if (resume_) return trainer_->lesson();
    return trainer_->chosen_case();
}

VolumePair TrainerWindow::load_volumes(const gpu::ContextOptions& gpu, TerminalProgress& progress)
{
    const exam::Scenario& c = case_to_load();
    if (!args_.volume.empty()) {
        // the user's own volume serves every case (its labels judge the compression)
        if (!volumes_.volume) volumes_ = user_volume(args_.volume, args_.labels);
        loaded_ = c.id;
        return volumes_;
    }
    const bool first = !preparer_;
    if (first) {
        const bool coarse = args_.coarse;
        preparer_ = std::make_unique<VolumePreparer>(
            [coarse, gpu](const exam::Scenario& s, const VolumePreparer::Progress& p) { return exam_volume(s, coarse, gpu, p); },
            [coarse](const exam::Scenario& s) { return exam_volume_cached(s, coarse); });
        if (args_.kiosk) preparer_->also_make(trainer_->cases());  // a kiosk's trainees never wait
        trainer_->set_readiness([this](const exam::Scenario& s) { return readiness(s); });
    }
    if (loaded_ == c.id && volumes_.volume) return volumes_;
    placeholder_ = false;
    if (std::optional<VolumePair> held = preparer_->take(c.id)) {
        volumes_ = std::move(*held);
    } else if (!first || exam_volume_cached(c, args_.coarse)) {
        // read from the cache at once (a few seconds at most); a runner is asked for a case only
        // once the preparer holds it, so later runners take theirs above
        volumes_ = exam_volume(c, args_.coarse, gpu, progress);
    } else {
        // the window opens now, its volume an empty one far from the leg, while the chosen case's
        // is made (the start screen shows how far)
        preparer_->want(c);
        auto empty = std::make_shared<io::Volume>();
        empty->size = {2, 2, 2};
        empty->origin = glm::dvec3(1e5);
        empty->data.assign(8, 0);
        volumes_ = {empty, nullptr, "none yet: case " + c.id + "'s volume is being made (once; it is cached), the start screen shows how far"};
        placeholder_ = true;
        loaded_.clear();
        return volumes_;
    }
    loaded_ = c.id;
    return volumes_;
}

std::string TrainerWindow::made_line() const
{
    // (a kiosk's: only it makes every case, also_make)
    const auto [made, all] = preparer_ ? preparer_->made() : std::pair<int, int>{0, 0};
    if (all == 0 || made >= all) return {};
    return "Images made for " + std::to_string(made) + " of " + std::to_string(all) +
           " cases; the others are being made behind this screen, once (then kept).";
}

trainer::CaseReadiness TrainerWindow::readiness(const exam::Scenario& c) const
{
    if (!preparer_) return {};
    if (c.id == loaded_ && volumes_.volume) return {true, made_line()};
    const VolumePreparer::Status st = preparer_->status(c.id);
    switch (st.state) {
    case VolumePreparer::State::ready: return {true, made_line()};
    case VolumePreparer::State::making:
        return {false, "This case's images are being made, once (then kept): " + st.stage + ".", st.done};
    case VolumePreparer::State::failed: return {false, "This case's images could not be made: " + st.error};
    case VolumePreparer::State::waiting: break;
    }
    return {false, "This case's images are to be made next, once (then kept)."};
}

void TrainerWindow::configure(runner::RunnerConfig& config)
{
    const exam::Scenario& c = case_to_load();
    config.session.patient.venous_pressure_mmHg = c.patient.venous_pressure_mmHg;
    config.session.patient.heart_rate_bpm = c.patient.heart_rate_bpm;
    // the image as the case asks for it, unless the command line says (run_window checked the name);
    // a user's volume without labels can only be sliced
    config.imaging = !args_.imaging.empty() ? std::optional(echo::parse_imaging(args_.imaging)) : c.imaging;
    config.volume_pending = placeholder_;
    if (!volumes_.labels) config.imaging = echo::Imaging::interpolative;
    if (args_.kiosk) {
        config.window.fullscreen = true;
        if (GLFWmonitor* m = glfwGetPrimaryMonitor())
            if (const GLFWvidmode* mode = glfwGetVideoMode(m)) {
                config.window.width = std::min(mode->width, 3840);
                config.window.height = std::min(mode->height, 2160);
            }
    }
    trainer::DriverOptions d;
    d.loaded_case = loaded_;
    d.volume = volumes_.volume;
    d.labels = volumes_.labels;
    d.patient = config.session.patient;
    const bool kiosk = args_.kiosk;
    // the UI's scale, read once the window is open (the factory runs then): the monitor's content
    // scale; the kiosk's at least its height over 1080 (a 4K kiosk read standing)
    d.ui_scale = [kiosk]() {
        float sx = 1, sy = 1;
        if (GLFWmonitor* m = glfwGetPrimaryMonitor()) glfwGetMonitorContentScale(m, &sx, &sy);
        float s = std::max(1.0f, sy);
        if (kiosk)
            if (GLFWmonitor* m = glfwGetPrimaryMonitor())
                if (const GLFWvidmode* mode = glfwGetVideoMode(m)) s = std::max(s, float(std::min(mode->height, 2160)) / 1080.0f);
        return std::clamp(s, 1.0f, 4.0f);
    };
    driver_ = std::make_shared<trainer::TrainerDriver>(trainer_, d);
    if (!args_.volume.empty()) driver_->accept_any_case();
    config.observers.push_back(driver_);
    for (runner::PassFactory& f : driver_->passes()) config.passes.push_back(std::move(f));
}

void TrainerWindow::attach(runner::Runner& runner)
{
    input_ = std::make_unique<UiWindowInput>(runner.window()->handle());
    if (resume_) {
        trainer_->restart(runner.session().time());
        resume_ = false;
    }
}

void TrainerWindow::detach()
{
    input_.reset();
    resume_ = again() && trainer_->screen() == trainer::Screen::exam;  // not the first runner's giving way
    // the run ends mid-lesson (the window closed, Ctrl+Alt+Q, a signal): the lesson is scored and
    // stored as it stands, as the idle timeout stores it
    if (!resume_ && trainer_->screen() == trainer::Screen::exam) {
        trainer_->finish(true);
        std::printf("echosim run: the lesson under way was stored%s: %s\n", trainer_->stored_id() ? "" : " (not in the records)",
                    (trainer_->report_dir() / "report.html").c_str());
        if (!trainer_->last_error().empty()) std::fprintf(stderr, "echosim run: %s\n", trainer_->last_error().c_str());
    }
}

void TrainerWindow::read_ui()
{
    typed_ = {};
    if (!input_ || !driver_) return;
    typed_ = input_->poll();
    driver_->feed(typed_);
    log_screen();
    if (!preparer_) return;
    log_made();
    // the making waits while a lesson runs (its cores are the exam's); on the start screen it
    // makes the case chosen there, and the first runner gives way once that case is ready
    const bool start = trainer_->screen() == trainer::Screen::start;
    const exam::Scenario& chosen = trainer_->chosen_case();
    preparer_->pause(trainer_->screen() == trainer::Screen::exam);
    if (start) preparer_->want(chosen);
    if (placeholder_ && start && !driver_->case_wanted() && trainer_->readiness(chosen).ready) driver_->want_case(chosen.id);
    // while a volume is made, the start screen is drawn at most kMakingFrameRate a second: on
    // lavapipe its frames take the cores the making needs (a case's volume behind a 1080p start
    // screen drawn at 32 frames/s took 49 s, alone 27 s; bench/RESULTS.md)
    const auto now = std::chrono::steady_clock::now();
    if (start && preparer_->busy()) std::this_thread::sleep_until(last_ui_ + std::chrono::microseconds(long(1e6 / kMakingFrameRate)));
    last_ui_ = std::max(now, std::chrono::steady_clock::now());
}

void TrainerWindow::log_made()
{
    // a kiosk's log says how far the cases' images are, as the making goes (an instructor setting
    // it up knows when every case starts at once)
    const auto [made, all] = preparer_->made();
    if (all == 0 || made == logged_made_) return;
    logged_made_ = made;
    std::printf("echosim run: the cases' images: %d of %d made%s\n", made, all, made < all ? ", the others being made behind the start screen" : "");
    std::fflush(stdout);
}

void TrainerWindow::log_screen()
{
    // a step after the change (the trainer changes screen in the runner's step): a kiosk's log
    // says who did which lesson when, line by line
    const trainer::Trainer& t = *trainer_;
    if (t.screen() == logged_) return;
    logged_ = t.screen();
    if (logged_ == trainer::Screen::exam) {
        std::printf("echosim run: a lesson started: %s on case %s, trainee '%s'\n", exam::protocol_name(t.form().lesson), t.lesson().id.c_str(),
                    t.form().trainee.c_str());
    } else if (logged_ == trainer::Screen::report) {
        std::printf("echosim run: the lesson finished: scored %.0f %% (pass mark %.0f %%), %s; report: %s\n", 100 * t.report().score,
                    100 * t.lesson().bands.pass_mark, t.stored_id() ? "stored in the records" : "not stored in the records",
                    (t.report_dir() / "report.html").c_str());
    }
    std::fflush(stdout);
}

void TrainerWindow::filter(runner::Runner&, RunInput& in)
{
    if (!input_ || !driver_) return;
    const ui::UiInput& typed = typed_;
    const ui::UiPass* ui = driver_->ui();
    if (ui && ui->wants_text() && (!typed.chars.empty() || !typed.pressed.empty() || !typed.held.empty())) {
        // a name being typed: its letters are no probe, scanner or window keys
        in.probe = {};
        in.scanner = {};
        in.reset_camera = false;
        in.toggle_fullscreen = false;
        in.quit = false;
    }
    if ((ui && ui->wants_mouse()) || driver_->caliper_hovered()) {  // a click on the frozen image is the caliper's
        in.orbit_yaw = in.orbit_pitch = 0;
        in.zoom = 1;
    }
    if (args_.kiosk) {
        in.quit = false;  // Esc: the instructor's Ctrl+Alt+Q alone ends a kiosk
        in.toggle_fullscreen = false;
        in.fullscreen.reset();
    }
}

}  // namespace echosim::app

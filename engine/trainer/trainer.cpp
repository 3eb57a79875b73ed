#include "trainer/trainer.hpp"

#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "exam/course_truth.hpp"
#include "scene/leg.hpp"

namespace echosim::trainer {
namespace {

// splitmix64: the random case's draw, the same for the same seed and count on every machine
std::uint64_t mix(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

std::string utc_stamp(const char* format)
{
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[40];
    std::strftime(buf, sizeof buf, format, &tm);
    return buf;
}

// the probe moved this far [mm] counts as activity (a hand resting on a device still trembles less)
constexpr double kActiveMoveMm = 1.0;

}  // namespace

const char* screen_name(Screen s)
{
    switch (s) {
    case Screen::start: return "start";
    case Screen::exam: return "exam";
    case Screen::report: return "report";
    }
    return "?";
}

Trainer::Trainer(TrainerOptions options) : options_(std::move(options))
{
    if (options_.cases.empty()) throw std::invalid_argument("trainer: no case to choose from");
    for (const std::filesystem::path& f : options_.cases) cases_.push_back(exam::read_scenario(f));
}

bool Trainer::select_case(const std::string& id)
{
    if (id == "random") {
        form_.case_index = -1;
        return true;
    }
    for (std::size_t i = 0; i < cases_.size(); ++i)
        if (cases_[i].id == id) {
            form_.case_index = int(i);
            return true;
        }
    return false;
}

const exam::Scenario& Trainer::chosen_case() const
{
    if (form_.case_index >= 0 && std::size_t(form_.case_index) < cases_.size()) return cases_[std::size_t(form_.case_index)];
    return cases_[std::size_t(mix(options_.seed + draws_) % cases_.size())];
}

void Trainer::start(double time_s)
{
    const exam::Scenario& c = chosen_case();
    lesson_ = lesson_scenario(c, form_.lesson);
    if (form_.case_index < 0) ++draws_;
    ++lessons_;
    restart(time_s);
}

Action Trainer::request_start(double time_s)
{
    if (!readiness(chosen_case()).ready) {
        start_waiting_ = true;
        return Action::none;
    }
    start(time_s);
    return Action::started;
}

void Trainer::restart(double time_s)
{
    start_waiting_ = false;
    const scene::LegModel leg;
    const echo::Phantom phantom(leg, lesson_.anatomy);
    scorer_ = std::make_unique<exam::Scorer>(lesson_, exam::station_truth(phantom, lesson_));
    started_s_ = time_s;
    last_active_s_ = time_s;
    last_ = {};
    report_ = {};
    report_dir_.clear();
    stored_id_ = 0;
    earlier_.clear();
    error_.clear();
    message_.clear();
    screen_ = Screen::exam;
}

void Trainer::observe(const exam::ExamSample& sample)
{
    if (screen_ != Screen::exam) return;
    scorer_->observe(sample);
    last_ = sample;
    last_.echo = nullptr;  // the step's frame is the session's, gone after the step
}

void Trainer::call(double time_s, exam::Call c)
{
    if (screen_ != Screen::exam) return;
    scorer_->call(time_s, c);
    last_active_s_ = time_s;
}

bool Trainer::station_done(std::size_t i) const
{
    const exam::Scorer::StationProgress p = scorer_->progress(i);
    return p.reached && p.peak_force_N >= lesson_.bands.adequate_force_N && p.call != exam::Call::none;
}

bool Trainer::station_wrong(std::size_t i) const
{
    const exam::Scorer::StationProgress p = scorer_->progress(i);
    const exam::StationTruth& t = scorer_->truth()[i];
    const bool wrong_call = p.call != exam::Call::none && (p.call == exam::Call::not_compressible) != t.thrombosed;
    return wrong_call || p.excessive || p.oblique || p.wrong_vessel;
}

std::optional<std::size_t> Trainer::target() const
{
    if (!scorer_) return std::nullopt;
    for (std::size_t i = 0; i < scorer_->truth().size(); ++i)
        if (!station_done(i)) return i;
    return std::nullopt;
}

void Trainer::finish(bool to_start)
{
    if (screen_ != Screen::exam) return;
    // the report's folder: the time (or, in repeatable runs, the lesson's number) and the case
    char name[160];
    if (options_.stamp_time) std::snprintf(name, sizeof name, "%s-%s", utc_stamp("%Y%m%d-%H%M%S").c_str(), lesson_.id.c_str());
    else std::snprintf(name, sizeof name, "%03d-%s", lessons_, lesson_.id.c_str());
    report_dir_ = options_.reports / name;
    try {
        if (!make_report_) throw std::logic_error("trainer: no way to make the report was given");
        report_ = make_report_(*scorer_, report_dir_, form_.trainee);
    } catch (const std::exception& e) {
        error_ = std::string("the report could not be written: ") + e.what();
        report_ = scorer_->finish({}, {});
        report_.trainee = form_.trainee;
    }
    if (options_.stamp_time && report_.started_utc.empty()) report_.started_utc = utc_stamp("%Y-%m-%dT%H:%M:%SZ");
    if (!options_.records.empty()) {
        try {
            exam::Records records(options_.records);
            stored_id_ = exam::store_exam(records, report_);
            earlier_ = records.sessions(form_.trainee);
        } catch (const std::exception& e) {
            error_ += (error_.empty() ? "" : "; ") + std::string("not stored in the records: ") + e.what();
        }
    }
    if (to_start) {
        char line[200];
        std::snprintf(line, sizeof line, "The last lesson was left idle: scored %.0f %% and %s.", 100 * report_.score,
                      stored_id_ ? "stored in the records" : "not stored");
        message_ = line;
        screen_ = Screen::start;
    } else {
        screen_ = Screen::report;
    }
}

void Trainer::new_lesson()
{
    screen_ = Screen::start;
    start_waiting_ = false;
    message_.clear();
    report_images_ = false;
}

Action Trainer::keys(const ui::UiInput& in, double time_s, bool text_active)
{
    using ui::Key;
    if (in.ctrl && in.alt && in.was_pressed(ui::letter('q'))) return Action::quit;
    if (!options_.kiosk && in.was_pressed(Key::escape) && !text_active) return Action::quit;
    switch (screen_) {
    case Screen::start: {
        const int n = int(cases_.size());
        if (in.was_pressed(Key::f1)) form_.lesson = exam::Protocol::two_point;
        if (in.was_pressed(Key::f2)) form_.lesson = exam::Protocol::three_point;
        if (in.was_pressed(Key::f3)) form_.lesson = exam::Protocol::extended;
        if (in.was_pressed(Key::f4)) form_.case_index = form_.case_index <= 0 ? n - 1 : form_.case_index - 1;
        if (in.was_pressed(Key::f5)) form_.case_index = form_.case_index < 0 || form_.case_index >= n - 1 ? 0 : form_.case_index + 1;
        if (in.was_pressed(Key::f6)) form_.case_index = -1;
        if (in.was_pressed(Key::f7)) form_.difficulty = Difficulty((int(form_.difficulty) + 1) % 3);
        if (in.was_pressed(Key::enter)) return request_start(time_s);
        return Action::none;
    }
    case Screen::exam:
        if (!text_active) {
            if (in.was_pressed(ui::letter('c'))) call(time_s, exam::Call::compressible);
            if (in.was_pressed(ui::letter('n'))) call(time_s, exam::Call::not_compressible);
            if (in.was_pressed(ui::letter('h'))) guidance_on_ = !guidance_on_;
        }
        if (in.was_pressed(Key::end)) {
            finish();
            return Action::finished;
        }
        return Action::none;
    case Screen::report:
        if (in.was_pressed(ui::letter('i'))) toggle_report_images();
        if (in.was_pressed(Key::enter)) new_lesson();
        return Action::none;
    }
    return Action::none;
}

Action Trainer::tick(double time_s, bool active)
{
    if (screen_ == Screen::exam) {
        const Pose& p = last_.face;
        if (glm::length(p.position - last_pose_.position) > float(kActiveMoveMm) || last_.force_N > exam::kContactForceN) active = true;
        if (active) last_pose_ = p;
    }
    if (active) last_active_s_ = time_s;
    if (screen_ == Screen::start && start_waiting_ && readiness(chosen_case()).ready) {
        start(time_s);
        return Action::started;
    }
    if (options_.idle_timeout_s <= 0 || time_s - last_active_s_ < options_.idle_timeout_s) return Action::none;
    last_active_s_ = time_s;
    if (screen_ == Screen::exam) {
        finish(true);
        return Action::finished;
    }
    if (screen_ == Screen::report) new_lesson();
    return Action::none;
}

}  // namespace echosim::trainer

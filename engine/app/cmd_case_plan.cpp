// `echosim case plan`: the scripted exams of a case (exam/exam_script.hpp, plan_exam), the correct
// one and one for each classic error, each station pressed as deep as the simulated tissue needs to
// push back with a force inside the case's adequate band (found on the session's own physics, in
// lock-step: Session::press_to_force), so the shipped scripts stay right when the tissue model or
// a case's bands change: `echosim case plan --all assets/cases/trajectories` writes them anew.
#include <cstdio>
#include <optional>

#include <glm/geometric.hpp>

#include "app/commands.hpp"
#include "app/exam_run.hpp"
#include "exam/course_truth.hpp"
#include "exam/exam_script.hpp"
#include "io/partial_file.hpp"
#include "session/session.hpp"

namespace echosim::app {
namespace {

// Where in the adequate band a correct exam presses: above its floor by a margin a trainee's
// steady hand keeps, well below the excessive limit.
constexpr double kBandFraction = 0.55;

session::Session planning_session()
{
    return session::Session(session::SessionOptions{.clock = session::Clock::lock_step, .window_follows_probe = true});
}

// The probe sent to `to` and given the time the physics' probe sweep needs to get there, and more.
void go(session::Session& session, const Pose& to, const exam::PlanOptions& plan)
{
    const double mm = glm::length(session.probe().face().position - to.position);
    session.place_probe({to, 0.0});
    session.advance(0.2 + mm / plan.far_speed_mm_s);
}

// The depth a probe resting at `rest` needs for `target_N`, the deepest press when it is out of reach.
double press_depth(session::Session& session, const Pose& rest, double target_N)
{
    try {
        return session.press_to_force(rest, target_N).press_mm;
    } catch (const std::invalid_argument&) {
        return session::Session::kMaxPressMm;  // what a trainee can give there
    }
}

// Each station's press depth [mm] for `target_N` there.
std::vector<double> press_depths(const PreparedExam& exam, double target_N)
{
    session::Session session = planning_session();
    std::vector<double> depths;
    const exam::PlanOptions plan;
    std::optional<Pose> previous;
    for (const exam::StationTruth& t : exam.truth) {
        // to the station as the planned exam goes there: lifted, and round the limb when it turns far
        if (previous && exam::turns_far(*previous, t.ideal_probe, plan)) {
            go(session, pressed_along_beam(*previous, -plan.far_lift_mm), plan);
            go(session, pressed_along_beam(t.ideal_probe, -plan.far_lift_mm), plan);
        }
        go(session, pressed_along_beam(t.ideal_probe, -plan.lift_mm), plan);
        previous = t.ideal_probe;
        depths.push_back(press_depth(session, t.ideal_probe, target_N));
        session.place_probe({pressed_along_beam(t.ideal_probe, -plan.lift_mm), 0.0});
        session.advance(0.2);
    }
    return depths;
}

exam::PlanError parse_style(const std::string& style)
{
    for (exam::PlanError e : {exam::PlanError::none, exam::PlanError::skip, exam::PlanError::light_press, exam::PlanError::oblique,
                              exam::PlanError::artery, exam::PlanError::excessive, exam::PlanError::mimic_called})
        if (style == exam::plan_error_name(e)) return e;
    throw std::invalid_argument("--style " + style + ": correct, skip, light-press, oblique, artery, excessive or mimic-called");
}

// The depth a probe resting at `rest` needs for `target_N`, on its own session (the oblique error's
// tilted press, the excessive one's).
double depth_for(const Pose& rest, double target_N)
{
    session::Session session = planning_session();
    const exam::PlanOptions plan;
    // the lifted approach timed by the way to the rest pose itself (as the shipped scripts were made)
    const double mm = glm::length(session.probe().face().position - rest.position);
    session.place_probe({pressed_along_beam(rest, -plan.lift_mm), 0.0});
    session.advance(0.2 + mm / plan.far_speed_mm_s);
    return press_depth(session, rest, target_N);
}

void write_plan(const PreparedExam& exam, const std::vector<double>& depths, exam::PlanError error, std::size_t at,
                const std::filesystem::path& out)
{
    exam::PlanOptions o;
    o.error = error;
    o.at = at;
    // a tilted face's edge overshoots on the way in (half again the settled force, measured): aimed
    // at the band's bottom tenth, its peak stays inside the band
    const exam::ScoringBands& b = exam.scenario.bands;
    if (error == exam::PlanError::oblique)
        o.oblique_press_mm = depth_for(exam::tilted_about_array(exam.truth[at].ideal_probe, o.oblique_deg),
                                       b.adequate_force_N + 0.1 * (b.excessive_force_N - b.adequate_force_N));
    // past the excessive limit by a margin no settling ripple hides
    if (error == exam::PlanError::excessive)
        o.excessive_press_mm = depth_for(exam.truth[at].ideal_probe, 1.15 * exam.scenario.bands.excessive_force_N);
    io::write_file<std::runtime_error>(out, exam::format_exam_script(exam::plan_exam(exam.truth, depths, o)));
    std::printf("echosim case plan: %s: %s%s\n", out.c_str(), exam::plan_error_name(error),
                error == exam::PlanError::none ? "" : (" at " + exam.truth[at].name).c_str());
}

// The station a case's error trajectory errs at: one inside the exam (not its first), and for the
// mimic the station beside the lymph node, for the artery one where the artery lies beside the vein.
std::size_t error_station(const PreparedExam& exam, exam::PlanError error)
{
    for (std::size_t i = 0; i < exam.truth.size(); ++i) {
        const exam::StationTruth& t = exam.truth[i];
        if (error == exam::PlanError::mimic_called && t.mimic_nearby && !t.thrombosed) return i;
        if (error == exam::PlanError::artery && t.artery.radius_mm > 0 && i > 0 && !t.thrombosed) return i;
        if (error != exam::PlanError::mimic_called && error != exam::PlanError::artery && i > 0 && !t.thrombosed) return i;
    }
    return exam.truth.size();  // none fits
}

}  // namespace

int run_case_plan(const CasePlanArgs& args)
{
    const char* me = "echosim case plan";
    try {
        std::vector<std::string> ids;
        if (!args.all.empty()) {
            for (const std::filesystem::path& f : exam::shipped_cases()) ids.push_back(f.stem().string());
        } else {
            ids.push_back(args.case_id.empty() ? "healthy" : args.case_id);
        }
        for (const std::string& id : ids) {
            // the script file is not needed to plan one: the case and its truth are
            PreparedExam exam;
            exam.scenario = args.scenario.empty() || !args.all.empty() ? exam::read_scenario(exam::shipped_case(id))
                                                                       : exam::read_scenario(args.scenario);
            const scene::LegModel leg;
            const echo::Phantom phantom(leg, exam.scenario.anatomy);
            exam.truth = exam::station_truth(phantom, exam.scenario);
            const exam::ScoringBands& b = exam.scenario.bands;
            const double target_N = b.adequate_force_N + kBandFraction * (b.excessive_force_N - b.adequate_force_N);
            const std::vector<double> depths = press_depths(exam, target_N);
            if (args.all.empty()) {
                const exam::PlanError error = parse_style(args.style);
                const std::size_t at = args.at >= 0 ? std::size_t(args.at) : error_station(exam, error);
                if (error != exam::PlanError::none && at >= exam.truth.size())
                    throw std::invalid_argument("--at: no station of case " + exam.scenario.id + " fits the error " + args.style);
                write_plan(exam, depths, error, at, args.out);
                continue;
            }
            std::filesystem::create_directories(args.all);
            write_plan(exam, depths, exam::PlanError::none, 0, args.all / (exam.scenario.id + ".correct.csv"));
            for (exam::PlanError e : {exam::PlanError::skip, exam::PlanError::light_press, exam::PlanError::oblique, exam::PlanError::artery,
                                      exam::PlanError::excessive, exam::PlanError::mimic_called}) {
                const std::size_t at = error_station(exam, e);
                if (at >= exam.truth.size()) continue;  // e.g. no lymph node in this case
                write_plan(exam, depths, e, at, args.all / (exam.scenario.id + "." + exam::plan_error_name(e) + ".csv"));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", me, e.what());
        return kExitBadInput;
    }
    return kExitOk;
}

}  // namespace echosim::app

// `echosim exam` (DESIGN.md §4): a scripted exam, headless, repeatable to the byte (app/exam_run.hpp),
// its report written and the exam stored in the trainee records.
#include <cstdio>

#include "app/commands.hpp"
#include "app/exam_run.hpp"
#include "app/exam_volume.hpp"
#include "app/gpu_args.hpp"
#include "app/stop_signals.hpp"
#include "app/terminal_progress.hpp"
#include "exam/records.hpp"
#include "exam/report_writer.hpp"

namespace echosim::app {

int run_exam(const ExamArgs& args)
{
    const char* me = "echosim exam";
    if (!(args.frames_per_s >= 0 && args.frames_per_s <= 60)) {
        std::fprintf(stderr, "%s: --frames-per-s %g: 0 (images at the stations only) to 60\n", me, args.frames_per_s);
        return kExitBadInput;
    }
    // every input read and checked before any work
    PreparedExam exam;
    try {
        exam = prepare_exam(args.scenario, args.case_id, args.seed, args.trajectory);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", me, e.what());
        return kExitBadInput;
    }
    std::error_code made;
    std::filesystem::create_directories(args.out, made);
    if (made) {
        std::fprintf(stderr, "%s: --out %s: cannot make the folder: %s\n", me, args.out.c_str(), made.message().c_str());
        return kExitBadInput;
    }
    if (!output_path_usable("exam", "--out", args.out / exam::kReportJson)) return kExitBadInput;
    std::printf("%s: %s (%s), %s protocol, %zu stations; script %s (%.1f s)\n", me, exam.scenario.title.c_str(), exam.scenario.id.c_str(),
                exam::protocol_name(exam.scenario.protocol), exam.truth.size(), exam.trajectory_name.c_str(), exam.trajectory.end_s());

    VolumePair volumes;
    {
        TerminalProgress progress(std::string(me) + ": making the case's volume (once; it is cached): ");
        try {
            volumes = exam_volume(exam.scenario, args.coarse, context_options(args.gpu), progress);
        } catch (const std::exception& e) {
            progress.finish();
            std::fprintf(stderr, "%s: %s\n", me, e.what());
            return kExitFailure;
        }
        progress.finish();
    }
    std::printf("%s: echographic volume: %s\n", me, volumes.description.c_str());

    const StopSignals stop;
    ExamRunResult r;
    try {
        ExamRunOptions o{.frames_per_s = args.frames_per_s, .out = args.out, .gpu = context_options(args.gpu), .trainee = args.trainee,
                         .stop = &stop};
        if (!args.imaging.empty()) o.imaging = echo::parse_imaging(args.imaging);
        r = perform_exam(exam, volumes, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", me, e.what());
        return kExitFailure;
    }
    if (r.stopped) {
        std::printf("%s: stopped by %s; no report written\n", me, StopSignals::name(stop.requested()));
        return StopSignals::exit_code(stop.requested());
    }
    const exam::ExamReport& report = r.report;
    std::printf("%s: %.1f s of exam in %.1f s (%lld frames), report in %.1f s\n", me, r.simulated_s, r.run_wall_s,
                static_cast<long long>(r.frames), r.report_wall_s);
    std::printf("%s: score %.0f %% (pass mark %.0f %%): %s; %zu error%s flagged\n", me, 100 * report.score, 100 * report.pass_mark,
                report.passed ? "passed" : "not passed", report.errors.size(), report.errors.size() == 1 ? "" : "s");
    for (const exam::FlaggedError& e : report.errors)
        std::printf("%s:   %s at %s: %s\n", me, exam::error_name(e.kind), e.station.empty() ? "the exam" : e.station.c_str(), e.detail.c_str());
    std::printf("%s: %s\n", me, report.conclusion.c_str());
    if (!args.no_records) {
        try {
            const std::filesystem::path db = args.records.empty() ? exam::default_records_path() : args.records;
            exam::Records records(db);
            exam::store_exam(records, report);
            std::printf("%s: stored in the trainee records %s\n", me, db.c_str());
        } catch (const std::exception& e) {
            // the report is written: say what failed, keep the exit code for it
            std::fprintf(stderr, "%s: %s\n", me, e.what());
            std::printf("%s: report: %s\n", me, (args.out / exam::kReportHtml).c_str());
            return kExitFailure;
        }
    }
    std::printf("%s: report: %s\n", me, (args.out / exam::kReportHtml).c_str());
    if (r.validation_messages > 0) {
        std::fprintf(stderr, "%s: Vulkan validation reported %u message(s)\n", me, r.validation_messages);
        return kExitValidation;
    }
    return kExitOk;
}

}  // namespace echosim::app

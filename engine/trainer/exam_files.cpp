#include "trainer/exam_files.hpp"

#include <cctype>
#include <cstdio>

#include "echo/echo_image_cpu.hpp"
#include "exam/report_writer.hpp"
#include "io/png.hpp"
#include "runner/recorders.hpp"

namespace echosim::trainer {

std::string station_image_name(std::size_t i, const std::string& station)
{
    // its number and its name, kept to characters every file system takes
    char head[32];
    std::snprintf(head, sizeof head, "%02zu-", i + 1);
    std::string name = head;
    for (char c : station) name += std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(static_cast<unsigned char>(c))) : '-';
    return "stations/" + name + ".png";
}

exam::ExamReport write_exam_report(const exam::Scorer& scorer, const io::Volume& volume, const io::Volume* labels,
                                   const echo::PatientCase& patient, const std::filesystem::path& out, const std::string& trainee,
                                   echo::Imaging imaging)
{
    std::filesystem::create_directories(out / "stations");
    const std::vector<exam::StationTruth>& truth = scorer.truth();
    const echo::ScannerSettings scanner;
    std::vector<std::optional<exam::Compression>> compression(truth.size());
    std::vector<std::string> images(truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const std::optional<echo::EchoFrame>& deepest = scorer.deepest_frame(i);
        if (!deepest) continue;
        // the image as deep as the trainee's was, or as the vein's lumen at rest needs (the rows
        // the same: the scanner's depth control's scale)
        echo::ImagePlane plane;
        plane.depth_mm = exam::station_image_depth_mm(truth[i], *deepest, scorer.deepest_image_depth_mm(i));
        // one image at the deepest press serves the report's picture and its deformed labels
        const echo::EchoImage pressed =
            echo::render_echo_cpu(volume, labels, plane, *deepest, scanner, patient, true, labels ? imaging : echo::Imaging::interpolative);
        if (labels) {
            const echo::EchoImage rest = echo::render_echo_cpu(volume, labels, plane, exam::unpressed(*deepest), scanner, patient, true);
            compression[i] = exam::measure_compression(truth[i], *deepest, plane, rest.labels, pressed.labels);
        }
        images[i] = station_image_name(i, truth[i].name);
        io::write_png(out / images[i], runner::to_rgba(pressed));
    }
    exam::ExamReport report = scorer.finish(compression, images);
    report.trainee = trainee;
    exam::write_report(report, out);
    return report;
}

}  // namespace echosim::trainer

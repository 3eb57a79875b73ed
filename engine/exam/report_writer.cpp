#include "exam/report_writer.hpp"

#include <system_error>

#include "exam/report_html.hpp"
#include "exam/report_json.hpp"
#include "exam/report_summary.hpp"
#include "io/partial_file.hpp"

namespace echosim::exam {

void write_report(const ExamReport& report, const std::filesystem::path& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw ReportError(dir.string() + ": cannot make the report's folder: " + ec.message());

    io::write_file<ReportError>(dir / kReportHtml, report_html(report, dir));
    const std::filesystem::path png = dir / kReportSummaryPng;
    io::RgbaImage summary;
    try {
        summary = report_summary(report, dir);
    } catch (const std::exception& e) {
        throw ReportError(png.string() + ": cannot draw it: " + e.what());
    }
    try {
        io::write_png(png, summary);
    } catch (const std::exception& e) {
        throw ReportError(e.what());  // io's message opens with the file already
    }
    io::write_file<ReportError>(dir / kReportJson, report_json(report));
}

}  // namespace echosim::exam

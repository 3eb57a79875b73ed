// The exam's report files in its output folder (DESIGN.md §3, "exam report"): report.json,
// report.html and summary.png. Each is written through a temporary renamed into place
// (io/partial_file.hpp), so a crash never leaves half a file; report.json is written last, so its
// presence says the folder's report is whole.
#pragma once

#include <filesystem>

#include "exam/exam_report.hpp"
#include "exam/report_json.hpp"

namespace echosim::exam {

inline constexpr const char* kReportJson = "report.json";
inline constexpr const char* kReportHtml = "report.html";
inline constexpr const char* kReportSummaryPng = "summary.png";

// Writes the three files into `dir` (made if missing), reading the stations' images (image_png,
// relative to `dir`) to embed them. Throws ReportError naming the file that failed.
void write_report(const ExamReport& report, const std::filesystem::path& dir);

}  // namespace echosim::exam

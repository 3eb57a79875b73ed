// report.html: the exam report a person opens in a browser, self-contained (inline CSS, inline SVG
// drawings, the stations' images as data: URIs), with no script, nothing fetched (its Content
// Security Policy forbids both), and every string from the case or the trainee escaped.
#pragma once

#include <filesystem>
#include <string>

#include "exam/exam_report.hpp"

namespace echosim::exam {

// The page. `dir` is the report's folder, where the stations' images (image_png) are read from; an
// image that cannot be embedded is named in its place with the reason.
std::string report_html(const ExamReport& report, const std::filesystem::path& dir);

}  // namespace echosim::exam

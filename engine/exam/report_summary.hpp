// summary.png: the exam on one page, for a printout or a message: the verdict and the conclusion,
// the force over time with the case's bands and the stations' deepest presses, the station table,
// the flagged errors, the motion, and the stations' images at their deepest press as thumbnails.
// Drawn with the project's plot and bitmap font (io/plot.hpp, io/bitmap_font.hpp): ASCII text
// only (other characters show as '?').
#pragma once

#include <filesystem>

#include "exam/exam_report.hpp"
#include "io/png.hpp"

namespace echosim::exam {

inline constexpr std::uint32_t kSummaryWidth = 1600;  // [px]; the height follows the content

// The page. `dir` is the report's folder, where the stations' images are read from; one that
// cannot be read is left out of the thumbnails and named there.
io::RgbaImage report_summary(const ExamReport& report, const std::filesystem::path& dir);

}  // namespace echosim::exam

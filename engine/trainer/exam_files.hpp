// A scored exam's report, as `echosim exam` and the trainer both write it (one source): each
// station's deepest press imaged on the CPU twin of the image pipeline (the same bytes on every
// machine), its picture written under stations/ and its deformed labels measured against the same
// plane at rest (exam::measure_compression), then the scorer's report with them, and report.json,
// report.html and summary.png (exam/report_writer.hpp) in the folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "echo/echo_frame.hpp"
#include "exam/exam_report.hpp"
#include "exam/scorer.hpp"
#include "io/nrrd.hpp"

namespace echosim::trainer {

// The station's image's name in the report's folder: "stations/03-fv-6-cm.png".
std::string station_image_name(std::size_t i, const std::string& station);

// Writes the stations' images (made as the exam showed them: `imaging`) and the report into `out`
// (made) and returns the report, the trainee named. `labels` null: no compression measured (and
// interpolative images only). Throws what writing throws (naming the file).
exam::ExamReport write_exam_report(const exam::Scorer& scorer, const io::Volume& volume, const io::Volume* labels,
                                   const echo::PatientCase& patient, const std::filesystem::path& out, const std::string& trainee,
                                   echo::Imaging imaging = echo::Imaging::interpolative);

}  // namespace echosim::trainer

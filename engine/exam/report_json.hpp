// report.json: the exam report as data (DESIGN.md §3, "exam report"). Keys in a fixed order and
// numbers at fixed decimals, so two runs of the same exam write the same bytes; no clock is read
// (started_utc is written as given: "" in repeatable runs). The force trace is not in it: the
// exam's force log (CSV) holds every sample, and the report keeps the peaks per station.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "exam/exam_report.hpp"

namespace echosim::exam {

// The decimals each kind of number is written with: below what the simulation resolves, above
// what a reader compares.
namespace report_decimals {
inline constexpr int time_s = 3;
inline constexpr int length_mm = 2;
inline constexpr int s_cm = 2;
inline constexpr int angle_deg = 2;
inline constexpr int force_N = 3;
inline constexpr int area_mm2 = 3;
inline constexpr int ratio = 4;
inline constexpr int score = 4;
inline constexpr int osaus = 2;
}  // namespace report_decimals

// A report that could not be written or read: the message opens with the file.
struct ReportError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The report.json text, ending with a newline. Strings that are not UTF-8 are written with U+FFFD
// in place of the bad bytes; JSON's escapes cover the rest.
std::string report_json(const ExamReport& report);

// A report.json read back into a report (`echosim records add` stores one: an exam run with
// --no-records, or on another machine): every field report_json writes but the derived ones
// (status), with the decimals it was written at; no force trace. A field missing or of the wrong
// type, or a file that is not an exam report, throws ReportError naming the file and the field.
ExamReport parse_report_json(const std::string& text, const std::filesystem::path& file_for_messages);
ExamReport read_report_json(const std::filesystem::path& file);

}  // namespace echosim::exam

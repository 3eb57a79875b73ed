// How a station of an exam went, in the words the report's leg map, its table and the records use.
// One definition for all of them, so the map's colours, the learning curve's successes and the xAPI
// statements never disagree about a station.
#pragma once

#include <cstddef>
#include <string>

#include "exam/exam_report.hpp"

namespace echosim::exam {

enum class StationStatus {
    covered,  // reached, and no error flagged there: the call right
    skipped,  // never reached
    wrong,    // reached, but the call wrong or an error flagged at the station
};
const char* station_status_name(StationStatus s);  // "covered", "skipped", "wrong"

StationStatus station_status(const ExamReport& report, std::size_t station);

// The station pressed hard enough: reached, and no too-little-pressure error flagged at it (the
// scorer judged the peak force against the case's adequate band, or the walls met).
bool adequately_pressed(const ExamReport& report, std::size_t station);
// Pressed within the case's bands: adequately pressed, and no excessive force flagged at it.
bool pressed_within_bands(const ExamReport& report, std::size_t station);

// A success in the learning curve's sense: reached, adequately pressed and called right.
bool station_success(const ExamReport& report, std::size_t station);

// The kind of station a learning curve counts together: the first word of its name, lower case
// ("CFV" -> "cfv", "FV 6 cm" -> "fv", "SFJ" -> "sfj", "Popliteal" -> "popliteal"), letters and
// digits only; a name without one takes its segment's name.
std::string station_type(const std::string& name, const std::string& segment);

}  // namespace echosim::exam

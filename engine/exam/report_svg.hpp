// The report's two drawings as inline SVG (report.html holds them; no file, no script, no network):
// the force over the exam's time with the stations' deepest presses and the case's force bands,
// and the leg map, a schematic of the proximal vein course with each station coloured by how it
// went (exam/station_status.hpp). Coordinates at one decimal, so the same report draws the same bytes.
#pragma once

#include <string>

#include "exam/exam_report.hpp"
#include "exam/station_status.hpp"
#include "io/bitmap_font.hpp"

namespace echosim::exam {

// The colour each station status is drawn in, shared by both drawings, the table and the PNG summary
// ("#rrggbb"), and the same as bytes for the pictures drawn on the CPU.
const char* status_colour(StationStatus s);
io::Rgba status_rgba(StationStatus s);

// An <svg> element, width x height in CSS pixels.
std::string force_trace_svg(const ExamReport& report, int width = 960, int height = 320);

// An <svg> element: the deep vein from the inguinal ligament down the common femoral vein, the
// saphenofemoral junction with the great saphenous vein going medial, the femoral bifurcation with
// the deep femoral vein going deep, the femoral vein to the adductor hiatus, and the popliteal vein
// behind the knee. The deep vein is drawn to scale along its s (ExamReport::course, when given;
// else its landmarks are placed from the stations' segments, and the map says it is schematic);
// a station on a branch sits along it by its s.
std::string leg_map_svg(const ExamReport& report);

}  // namespace echosim::exam

// The fit's report (paper Fig. 2 and Fig. 4): a text summary, statistics as JSON, the error
// histogram, and measured against fitted force-displacement curves for 11 points of both probes.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "fit/fit.hpp"

namespace echosim::fit {

std::string summary_text(const FitResult& result);

// The files a report is: report.json, error_histogram.png, curves_indenter.png, curves_probe.png.
inline constexpr std::array<const char*, 4> kReportFiles{"report.json", "error_histogram.png", "curves_indenter.png", "curves_probe.png"};

// Writes into `folder` (made if missing) the files of kReportFiles.
void write_report(const std::filesystem::path& folder, const MeasurementSet& set, const FitResult& result);

// The 11 points the curves show (spread over the grid, as in the paper's Fig. 2).
std::vector<int> curve_points();

}  // namespace echosim::fit

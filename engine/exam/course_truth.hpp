// The stations' truth from the case's phantom (exam/station_truth.hpp): for each station of the
// scenario, where its vein runs (centre, direction, calibre), the artery beside it and the great
// saphenous vein when near, whether a thrombus or a lymph node is there, and the transverse probe
// pose right above the vein. Also where the shipped cases' scripted exams are.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "echo/phantom.hpp"
#include "exam/scenario.hpp"
#include "exam/station_truth.hpp"

namespace echosim::exam {

std::vector<StationTruth> station_truth(const echo::Phantom& phantom, const Scenario& scenario);

// assets/cases/trajectories/ID.STYLE.csv: a shipped case's scripted exam ("correct", or one of
// plan_error_name's errors). Throws std::invalid_argument naming the file when there is none.
std::filesystem::path shipped_trajectory(const std::string& case_id, const std::string& style);

}  // namespace echosim::exam

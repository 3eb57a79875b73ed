// The tissue model the simulator runs: the shipped fitted parameters at the resolution the physics
// steps at in real time.
#pragma once

#include "core/skin_surface.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::session {

// 2500 nodes: the largest grid that steps at 1 kHz on one core (bench/RESULTS.md, physics).
inline constexpr int kSimulationRefine = 7;

// assets/models/thigh.json as read: the fitted parameters at the sample points, the fit's figures and
// provenance (build_simulation_model puts them on a patch); throws naming the file if it is missing
// or malformed.
tissue::TissueModel read_simulation_parameters();
// `fitted`'s parameters on `skin`'s exam patch at `refine`, with its fit and provenance.
tissue::TissueModel build_simulation_model(const SkinSurface& skin, const tissue::TissueModel& fitted, int refine = kSimulationRefine);

// assets/models/thigh.json's fitted parameters on `skin`'s exam patch; throws naming the file if it
// is missing or malformed.
tissue::TissueModel load_simulation_model(const SkinSurface& skin, int refine = kSimulationRefine);

}  // namespace echosim::session

// The tissue model the simulator runs: the shipped fitted parameters at the resolution the physics
// steps at in real time.
#pragma once

#include "core/skin_surface.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::session {

// 2500 nodes: the largest grid that steps at 1 kHz on one core (bench/RESULTS.md, physics).
inline constexpr int kSimulationRefine = 7;

// assets/models/thigh.json's fitted parameters on `skin`'s exam patch; throws naming the file if it
// is missing or malformed.
tissue::TissueModel load_simulation_model(const SkinSurface& skin, int refine = kSimulationRefine);

}  // namespace echosim::session

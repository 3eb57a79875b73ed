// Tissue models for the physics tests: the shipped fit on our leg at any refinement.
#pragma once

#include <filesystem>

#include "scene/leg.hpp"
#include "tissue/tissue_json.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::test {

inline const scene::LegModel& leg()
{
    static const scene::LegModel model;
    return model;
}

inline tissue::TissueModel shipped_model(int refine)
{
    const auto fitted = tissue::read_tissue_model(std::filesystem::path(ECHOSIM_ASSET_DIR) / "models" / "thigh.json");
    return tissue::build_tissue_model(leg(), fitted.samples, refine);
}

}  // namespace echosim::test

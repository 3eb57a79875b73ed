#include "session/simulation_model.hpp"

#include "core/assets.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::session {

tissue::TissueModel read_simulation_parameters() { return tissue::read_tissue_model(asset_path("models/thigh.json")); }

tissue::TissueModel build_simulation_model(const SkinSurface& skin, const tissue::TissueModel& fitted, int refine)
{
    tissue::TissueModel model = tissue::build_tissue_model(skin, fitted.samples, refine);
    model.fit = fitted.fit;
    model.provenance = fitted.provenance;
    return model;
}

tissue::TissueModel load_simulation_model(const SkinSurface& skin, int refine)
{
    return build_simulation_model(skin, read_simulation_parameters(), refine);
}

}  // namespace echosim::session

#include "session/simulation_model.hpp"

#include "core/assets.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::session {

tissue::TissueModel load_simulation_model(const SkinSurface& skin, int refine)
{
    const tissue::TissueModel fitted = tissue::read_tissue_model(asset_path("models/thigh.json"));
    tissue::TissueModel model = tissue::build_tissue_model(skin, fitted.samples, refine);
    model.fit = fitted.fit;
    model.provenance = fitted.provenance;
    return model;
}

}  // namespace echosim::session

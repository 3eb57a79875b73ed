// Stage 3: preconditioned conjugate gradient (block Jacobi) on the implicit step's system A dv = rhs,
// matrix-free through system_product, warm-started from the previous step's dv. Uses the state's
// scratch vectors; allocates nothing.
#pragma once

#include "physics/physics_options.hpp"
#include "physics/tissue_state.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

struct CgResult {
    int iterations = 0;
    double relative_residual = 0;
    bool finite = true;
};

// Solves for state.dv from state.rhs (fixed nodes' entries are zero in both).
CgResult conjugate_gradient(const tissue::TissueModel& model, const PhysicsOptions& options, const contact::PenaltyLaw& law,
                            TissueState& state, double h);

}  // namespace echosim::physics

// Stage 2: the implicit step's matrix applied to a vector, without assembling it:
//     A p = M p + h D p + h^2 K p        (the probe's contact included in D and K)
// with M the masses, D the damping and K the stiffness (both positive semi-definite: the negated
// force Jacobians), from the linearisation the force stage cached. Rows of fixed nodes are the
// identity on zero (Baraff and Witkin's filter), so A stays symmetric positive definite.
#pragma once

#include "physics/physics_options.hpp"
#include "physics/tissue_state.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

// Folds h into the cached linearisation (SpringLinearisation::iso and ::along, the same for the
// normal springs), once per step, so the products inside conjugate gradient do less work.
void prepare_system(const tissue::TissueModel& model, TissueState& state, double h);

void system_product(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& state, double h,
                    const Eigen::VectorXd& p, Eigen::VectorXd& out);

// K p alone (the stiffness, positive semi-definite), for the right-hand side h (f - h K v).
void stiffness_product(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& state,
                       const Eigen::VectorXd& p, Eigen::VectorXd& out);

// The inverses of A's 3 x 3 diagonal blocks, one per node: the block-Jacobi preconditioner. Blocks,
// not scalars, because the normal springs and the probe's contact act along directions that are not
// the world axes; a scalar diagonal would leave their stiffness badly conditioned.
void system_block_inverses(const tissue::TissueModel& model, const contact::PenaltyLaw& law, const TissueState& state,
                           double h, std::vector<Eigen::Matrix3d>& out);

}  // namespace echosim::physics

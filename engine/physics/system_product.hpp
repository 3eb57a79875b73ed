// Stage 2: the implicit step's matrix applied to a vector, without assembling it:
//     A p = M p + h D p + h^2 K p
// with M the masses, D the damping and K the stiffness (both positive semi-definite: the negated
// force Jacobians), from the linearisation the force stage cached. Rows of fixed nodes are the
// identity on zero (Baraff and Witkin's filter), so A stays symmetric positive definite.
#pragma once

#include "physics/physics_options.hpp"
#include "physics/tissue_state.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

void system_product(const tissue::TissueModel& model, const TissueState& state, double h, const Eigen::VectorXd& p,
                    Eigen::VectorXd& out);

// K v (the stiffness alone), for the right-hand side h (f + h K v)... with K negated: out = S v.
void stiffness_product(const tissue::TissueModel& model, const TissueState& state, const Eigen::VectorXd& p,
                       Eigen::VectorXd& out);

// The diagonal of A (3n), for the Jacobi preconditioner.
void system_diagonal(const tissue::TissueModel& model, const TissueState& state, double h, Eigen::VectorXd& out);

}  // namespace echosim::physics

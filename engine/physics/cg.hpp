// Stage 3: preconditioned conjugate gradient (block Jacobi) on the implicit step's system
// A dv = rhs, matrix-free through the grid system's product, warm-started from the previous step's
// dv. Vectors are plane vectors of floats (grid_system.hpp), sized once; a solve allocates nothing.
// Each iteration is three passes over memory: the product (with p . Ap); one fused pass that
// updates dv and the residual, applies the preconditioner and takes both dot products; and the new
// direction.
#pragma once

#include <vector>

#include "physics/compiled_model.hpp"
#include "physics/grid_system.hpp"

namespace echosim::physics {

struct CgVectors {
    std::vector<float> rhs, dv, residual, z, direction, product;  // 3n floats each, as planes
    ProductScratch scratch;  // the product's
};

CgVectors make_cg_vectors(const GridLayout& grid, int parts);

struct CgResult {
    int iterations = 0;
    double relative_residual = 0;
    bool finite = true;
};

// Solves A dv = rhs for vectors.dv, from its value on entry (rhs is zero at fixed nodes), to
// model.options' tolerances (relative to the right-hand side, or the absolute floor on the force
// left unbalanced); the passes are shared by `team`.
CgResult conjugate_gradient(const CompiledModel& model, const GridSystem& system, CgVectors& vectors, ForkJoin& team);

}  // namespace echosim::physics

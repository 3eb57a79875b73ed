// The physics' immutable model (MuJoCo's mjModel): everything the dynamics derives from the tissue
// model, the options and the contact's parameters, computed once and then only read. A step is
// step(const CompiledModel&, TissueState&, ForkJoin&) (step.hpp): the state (tissue_state.hpp)
// holds only what changes from step to step, and the thread team is the caller's.
//
// Shared: made by compile_model as a std::shared_ptr<const CompiledModel>, held by the physics
// runner, the tests and the benches alike; any number of states may step on one compiled model.
//
// One fixed mask: `free` (1 at a free node, 0 at one held to the leg), derived from
// tissue.boundary, which stays the definition. Every stage reads this one (the right-hand side, the
// system's masked product and preconditioner, the integration, the local contact model).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact/probe_contact.hpp"
#include "physics/grid_layout.hpp"
#include "physics/physics_options.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

// The constants of the tissue column under a node (the paper's eq. 1 spring along the rest normal n,
// and a linear shear spring across it); the non-linear spring's stiffness k, which changes with the
// compression, is the state's (TissueState::normal_stiffness). Blocks: stiffness k n n^T + k_t (I -
// n n^T), damping d n n^T + d_t (I - n n^T).
struct TissueColumn {
    Eigen::Vector3d n = Eigen::Vector3d::UnitY();  // outward rest normal
    double damping = 0;            // d [N s/mm]
    double lateral_stiffness = 0;  // k_t [N/mm]
    double lateral_damping = 0;    // d_t [N s/mm]
};

struct CompiledModel {
    tissue::TissueModel tissue;  // the definition it was compiled from (a copy: it lives as long as this)
    PhysicsOptions options;

    // the contact: the skin's triangles and samples, the probe's shape, the penalty law
    contact::PatchSurface surface;
    contact::ProbeGeometry probe;
    contact::PenaltyLaw penalty;

    GridLayout grid;                      // the model's springs as the grid's (grid_layout.hpp)
    Eigen::VectorXd rest;                 // rest positions, 3 per node [mm]
    std::vector<double> inv_mass_scaled;  // 1 / m, m in N s^2/mm (kg / 1000: F = m a in N and mm/s^2)
    std::vector<float> free;              // the fixed mask: 1 at a free node, 0 at a fixed one
    SpringPlanes spring_rest;             // per spring: rest length [mm], and 1 where the spring exists
    std::vector<TissueColumn> columns;    // per node

    std::size_t node_count() const { return grid.n; }
    bool fixed(std::size_t node) const { return free[node] == 0.0f; }
};

// Compiles the model; throws std::invalid_argument naming what does not fit (springs that are not
// the grid's, per-node arrays of the wrong size, a thread count out of range).
std::shared_ptr<const CompiledModel> compile_model(const tissue::TissueModel& model, const PhysicsOptions& options,
                                                   const contact::ProbeGeometry& probe = {},
                                                   const contact::PenaltyLaw& penalty = {});

}  // namespace echosim::physics

// The mutable state of the tissue dynamics, apart from the immutable CompiledModel (MuJoCo's mjData
// beside mjModel): what changes from step to step, and the solver's per-step coefficients and
// scratch. Every buffer a step needs is allocated here, when the state is made, so a step allocates
// nothing. What is derived from the model (rest positions, masses, the fixed mask, the grid, the
// springs' rest lengths, the tissue columns' constants) is the compiled model's; the threads that
// share a step are the caller's (step.hpp).
//
// Layout: positions, velocities and forces as Eigen vectors of 3n doubles (node i at 3i..3i+2).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "contact/probe_contact.hpp"
#include "physics/cg.hpp"
#include "physics/compiled_model.hpp"
#include "physics/grid_layout.hpp"
#include "physics/grid_system.hpp"
#include "physics/row_sweep.hpp"

namespace echosim::physics {

struct StepStats {
    bool asleep = false;  // the step only advanced the clock (PhysicsOptions::sleep_speed)
    int cg_iterations = 0;
    double cg_residual = 0;
    double probe_force_N = 0;  // the tissue's push on the probe, along the probe axis
    int contacts = 0;
};

struct TissueState {
    double time = 0;                 // [s]
    Eigen::VectorXd x, v;            // positions [mm], velocities [mm/s]
    Eigen::VectorXd external;        // forces applied from outside (tests, haptics) [N]
    contact::ProbeState probe;       // where the probe is, set by the caller before a step
    contact::ContactSet contacts;    // filled by the contact stage

    // scratch of the solver stages (sized once, for the model's options.threads parts)
    Eigen::VectorXd force;
    Eigen::VectorXd stiffness_v;  // K v, for the implicit step's right-hand side h (f - h K v)
    std::vector<double> node_scratch;  // one per node, zero between uses (local_contact_model)
    GridSystem system;  // A = M + h D + h^2 K for the step, in the grid's stencil form
    CgVectors cg;       // the solver's vectors; cg.dv is the last step's dv (the warm start)
    std::vector<double> x_planes, v_planes;  // x and v as plane vectors, for the springs' row sweep
    std::vector<RowBuffers<6>> spring_rows;   // the sweep's rows (force and K v), one per part of the team
    // the springs' linearisation, per spring: beta = max(0, 1 - rest / length) and the unit
    // direction e from the first node to the second; K_s = lambda (beta I + (1 - beta) e e^T),
    // D_s = mu e e^T
    SpringPlanes spring_linearisation;
    // per node, the tissue column's non-linear spring stiffness k = dF/dc [N/mm] at the compression
    // of the last linearisation (the column's constants are the model's: CompiledModel::columns)
    std::vector<double> normal_stiffness;
    bool constant_jacobian_ready = false;

    // Sleeping (PhysicsOptions::sleep_speed): the probe and external load the tissue has been still
    // under, and for how long [s] (reset whenever a node moves faster or either changes).
    contact::ProbeState still_probe;
    Eigen::VectorXd still_external;
    double still_for = 0;

    StepStats last;
    int resets = 0;   // NaNs and explosions detected and recovered from
    std::int64_t steps = 0;
};

// A state at rest for `model`, with buffers for a team of model.options.threads parts.
TissueState make_state(const CompiledModel& model);

// Back to rest: positions and velocities (and the solver's warm start); time and counters kept.
void reset_to_rest(const CompiledModel& model, TissueState& state);

}  // namespace echosim::physics

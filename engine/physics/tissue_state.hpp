// The mutable state of the tissue dynamics, apart from the immutable TissueModel and
// PhysicsOptions (MuJoCo's mjData beside mjModel). Every buffer a step needs is allocated here,
// when the state is made, so a step allocates nothing.
//
// Layout: positions, velocities and forces as Eigen vectors of 3n doubles (node i at 3i..3i+2).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact/probe_contact.hpp"
#include "core/fork_join.hpp"
#include "physics/cg.hpp"
#include "physics/grid_layout.hpp"
#include "physics/grid_system.hpp"
#include "physics/physics_options.hpp"
#include "physics/row_sweep.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

// Per-node support by the tissue column: the non-linear spring along the rest normal n (the paper's
// eq. 1) and a linear shear spring across it. Blocks: stiffness (k n n^T + k_t (I - n n^T)),
// damping (d n n^T + d_t (I - n n^T)).
struct NormalLinearisation {
    Eigen::Vector3d n = Eigen::Vector3d::UnitY();  // outward rest normal
    double stiffness = 0;          // k = dF/dc [N/mm], updated with the compression
    double damping = 0;            // d [N s/mm]
    double lateral_stiffness = 0;  // k_t [N/mm]
    double lateral_damping = 0;    // d_t [N s/mm]
};

struct StepStats {
    int cg_iterations = 0;
    double cg_residual = 0;
    double probe_force_N = 0;  // the tissue's push on the probe, along the probe axis
    int contacts = 0;
};

struct TissueState {
    double time = 0;                 // [s]
    Eigen::VectorXd x, v;            // positions [mm], velocities [mm/s]
    Eigen::VectorXd external;        // forces applied from outside (tests, haptics) [N]
    Eigen::VectorXd rest;                  // rest positions [mm]
    std::vector<double> inv_mass_scaled;   // 1 / m, m in N s^2/mm (kg / 1000: F = m a in N and mm/s^2)
    std::vector<std::uint8_t> fixed;       // rim nodes held to the leg
    contact::ProbeState probe;             // where the probe is, set by the caller before a step
    contact::ContactSet contacts;          // filled by the contact stage

    GridLayout grid;           // the model's springs as the grid's (grid_layout.hpp)
    SpringPlanes spring_rest;  // per spring: rest length [mm], and 1 where the spring exists

    // scratch of the solver stages (sized once)
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
    std::vector<NormalLinearisation> normals;
    bool constant_jacobian_ready = false;

    // the threads that share a step's sweeps (PhysicsOptions::threads); execution, not state, but
    // owned here so that a step needs nothing beyond the model, options, scene and state
    std::unique_ptr<ForkJoin> team;

    StepStats last;
    int resets = 0;   // NaNs and explosions detected and recovered from
    std::int64_t steps = 0;
};

struct Scene;
TissueState make_state(const tissue::TissueModel& model, const PhysicsOptions& options, const Scene& scene);

// Back to rest: positions, velocities and time; counters kept.
void reset_to_rest(TissueState& state);

}  // namespace echosim::physics

// Stage 1 of a step: the forces on every node and the linearisation the implicit solver needs.
//   surface springs    f = lambda (L - L0) - mu dL/dt, along the spring (paper eq. 2)
//   non-linear springs F(c) = c / (b - a c) along the rest normal, c the compression (eq. 1),
//                      and a linear shear spring across it (see PhysicsOptions)
//   gravity            m g
//   external           whatever the caller put in state.external (tests, haptic reaction)
// Alongside, K v (the stiffness blocks times the velocities) for the implicit step's right-hand
// side, while each spring's linearisation is at hand. The stiffness blocks are kept positive
// semi-definite, as conjugate gradient needs: the transverse term of a compressed surface spring
// (which would buckle it) is dropped (Choi and Ko 2002).
#pragma once

#include "core/fork_join.hpp"
#include "physics/compiled_model.hpp"
#include "physics/tissue_state.hpp"

namespace echosim::physics {

// The non-linear spring's compression is clamped to this fraction of its bottoming depth and
// continued linearly beyond, so a violent push cannot make the force infinite.
inline constexpr double kMaxCompressionFraction = 0.95;

// Into state.force and state.stiffness_v; with `update_linearisation`, the linearisation too
// (state.spring_linearisation, state.normal_stiffness), else the stored one is used. The sweeps are
// shared by `team`.
void accumulate_forces(const CompiledModel& model, TissueState& state, ForkJoin& team, bool update_linearisation);

// Potential energy of the springs [N mm = mJ] (for tests of energy decay).
double potential_energy(const CompiledModel& model, const TissueState& state);
double kinetic_energy(const CompiledModel& model, const TissueState& state);

}  // namespace echosim::physics

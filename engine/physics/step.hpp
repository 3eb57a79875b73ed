// One step of the tissue dynamics, reading like the paper's §4:
//   1. contact: where the probe face meets the skin, and the penalty forces (contact/)
//   2. forces and their linearisation (forces.cpp)
//   3. implicit: solve (M + h D + h^2 K) dv = h (f - h K v) by PCG (cg.cpp), then v += dv,
//      x += h v; explicit: v += h M^-1 f, x += h v
//   4. guard: a NaN or a node faster than options.max_speed resets the state to rest and is counted
// unless the tissue sleeps: still for options.sleep_after under the same probe and load, when the
// step only advances the clock (physics_options.hpp, sleep_speed).
// The model is read only (compiled_model.hpp); the state is written (tissue_state.hpp); the team is
// execution, the caller's: whoever steps owns it (PhysicsRunner, or a Simulation, simulation.hpp).
#pragma once

#include "core/fork_join.hpp"
#include "physics/compiled_model.hpp"
#include "physics/tissue_state.hpp"

namespace echosim::physics {

// Steps `state` by model.options.time_step, the sweeps shared by `team`. The team must have
// model.options.threads parts and the state must be made for `model` (make_state): both checked on
// entry, before anything is touched (std::invalid_argument: a wiring error, not a run-time
// condition; the step itself never throws and allocates nothing).
void step(const CompiledModel& model, TissueState& state, ForkJoin& team);
// One step of `stride` time steps at once (stride * options.time_step seconds; state.steps counts
// it as `stride`): what PhysicsRunner::step_to takes while the probe is clear of the skin
// (PhysicsOptions::clear_stride). std::invalid_argument for a stride below 1.
void step(const CompiledModel& model, TissueState& state, ForkJoin& team, int stride);

}  // namespace echosim::physics

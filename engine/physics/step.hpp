// One step of the tissue dynamics, reading like the paper's §4:
//   1. contact: where the probe face meets the skin, and the penalty forces (contact/)
//   2. forces and their linearisation (forces.cpp)
//   3. implicit: solve (M + h D + h^2 K) dv = h (f - h K v) by PCG (cg.cpp), then v += dv,
//      x += h v; explicit: v += h M^-1 f, x += h v
//   4. guard: a NaN or a node faster than options.max_speed resets the state to rest and is counted
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "contact/probe_contact.hpp"
#include "physics/physics_options.hpp"
#include "physics/tissue_state.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::physics {

// What a step needs besides the model and the state: the surface triangles and the probe's shape.
struct Scene {
    contact::PatchSurface surface;
    contact::ProbeGeometry probe;
    contact::PenaltyLaw penalty;
};

Scene make_scene(const tissue::TissueModel& model);

void step(const tissue::TissueModel& model, const PhysicsOptions& options, const Scene& scene, TissueState& state);

}  // namespace echosim::physics

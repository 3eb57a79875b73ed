// A compiled model with a state of its own and the team that steps it: a whole simulation stepped
// in the caller's thread, for tests, benches and lock-step tools (the physics runner holds the same
// three, and steps them on its thread). Movable, not copyable (the team's threads are its own).
#pragma once

#include <memory>

#include "core/fork_join.hpp"
#include "physics/compiled_model.hpp"
#include "physics/step.hpp"
#include "physics/tissue_state.hpp"

namespace echosim::physics {

struct Simulation {
    std::shared_ptr<const CompiledModel> model;
    TissueState state;
    std::unique_ptr<ForkJoin> team;  // model->options.threads parts

    // a state at rest, and a team of model->options.threads parts
    explicit Simulation(std::shared_ptr<const CompiledModel> compiled);

    void step() { physics::step(*model, state, *team); }
};

}  // namespace echosim::physics

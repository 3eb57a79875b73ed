#include "physics/simulation.hpp"

#include <stdexcept>
#include <utility>

namespace echosim::physics {

Simulation::Simulation(std::shared_ptr<const CompiledModel> compiled) : model(std::move(compiled))
{
    if (!model) throw std::invalid_argument("physics::Simulation: no compiled model");
    state = make_state(*model);
    team = std::make_unique<ForkJoin>(model->options.threads);
}

}  // namespace echosim::physics

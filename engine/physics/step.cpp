#include "physics/step.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/cg.hpp"
#include "physics/forces.hpp"
#include "physics/grid_system.hpp"

namespace echosim::physics {
namespace {

// The right-hand side h (f - h K v), zero at fixed nodes, into the solver's planes.
void right_hand_side(const CompiledModel& model, TissueState& s, ForkJoin& team)
{
    const double h = model.options.time_step;
    const std::size_t n = model.grid.n;
    float* rhs = s.cg.rhs.data();
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(model.grid, part, team.parts());
        for (std::size_t i = begin; i < end; ++i)
            for (std::size_t c = 0; c < 3; ++c)
                rhs[c * n + i] =
                    model.fixed(i) ? 0.0f : float(h * (s.force[Eigen::Index(3 * i + c)] - h * s.stiffness_v[Eigen::Index(3 * i + c)]));
    });
}

// v += dv, from the solver's planes.
void add_velocity_change(const CompiledModel& model, TissueState& s, ForkJoin& team)
{
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(model.grid, part, team.parts());
        add_planes_to(s.cg.dv.data(), model.grid.n, s.v.data(), begin, end);
    });
}

// x += h v, fixed nodes held still; true if a node has exploded (a NaN, or faster than
// options.max_speed).
bool advance(const CompiledModel& model, TissueState& s, ForkJoin& team)
{
    const double h = model.options.time_step;
    const double limit2 = model.options.max_speed * model.options.max_speed;
    std::array<std::uint8_t, ForkJoin::kMaxParts> exploded{};
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(model.grid, part, team.parts());
        for (std::size_t i = begin; i < end; ++i) {
            auto v = s.v.segment<3>(3 * Eigen::Index(i));
            if (model.fixed(i)) v.setZero();
            auto x = s.x.segment<3>(3 * Eigen::Index(i));
            x += h * v;
            if (!(v.squaredNorm() <= limit2) || !x.allFinite()) exploded[std::size_t(part)] = 1;  // (a NaN fails every comparison)
        }
    });
    return std::any_of(exploded.begin(), exploded.end(), [](std::uint8_t e) { return e != 0; });
}

// The wiring a step relies on: a team of the model's size and a state made for the model.
void check_wiring(const CompiledModel& model, const TissueState& s, const ForkJoin& team)
{
    if (team.parts() != model.options.threads || s.spring_rows.size() != std::size_t(model.options.threads))
        throw std::invalid_argument("physics step: a team of " + std::to_string(team.parts()) + " and a state for " +
                                    std::to_string(s.spring_rows.size()) + " parts, for a model of options.threads = " +
                                    std::to_string(model.options.threads));
    if (s.x.size() != model.rest.size() || s.normal_stiffness.size() != model.node_count())
        throw std::invalid_argument("physics step: a state of " + std::to_string(s.x.size() / 3) + " nodes for a model of " +
                                    std::to_string(model.node_count()));
}

}  // namespace

void step(const CompiledModel& model, TissueState& s, ForkJoin& team)
{
    check_wiring(model, s, team);
    const PhysicsOptions& options = model.options;
    const double h = options.time_step;
    const bool relinearise = options.jacobian == JacobianMode::updated || !s.constant_jacobian_ready;

    // 1-2: contact and forces (the contact stage adds its penalty forces after the internal ones)
    accumulate_forces(model, s, team, relinearise);
    s.constant_jacobian_ready = true;
    s.last.contacts = contact::collide(model.probe, model.penalty, s.probe, model.surface, s.x, s.v, s.contacts, s.force);
    s.last.probe_force_N = s.contacts.total_force;

    // 3: integrate
    if (options.integrator == Integrator::implicit_euler) {
        contact::add_contact_stiffness_product(s.contacts, s.v, s.stiffness_v);
        right_hand_side(model, s, team);
        prepare_system(model, s, s.system, team);
        const CgResult cg = conjugate_gradient(model, s.system, s.cg, team);
        s.last.cg_iterations = cg.iterations;
        s.last.cg_residual = cg.relative_residual;
        if (cg.finite) add_velocity_change(model, s, team);
        else s.v.setConstant(std::nan(""));  // the guard below resets and counts it
    } else {
        for (std::size_t i = 0; i < model.node_count(); ++i)
            s.v.segment<3>(3 * Eigen::Index(i)) += h * model.inv_mass_scaled[i] * s.force.segment<3>(3 * Eigen::Index(i));
        s.last.cg_iterations = 0;
    }

    // 4: positions, and the guard
    const bool exploded = advance(model, s, team);
    s.time += h;
    ++s.steps;
    if (exploded) {
        reset_to_rest(model, s);
        ++s.resets;
    }
}

}  // namespace echosim::physics

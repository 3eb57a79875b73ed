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
void right_hand_side(const CompiledModel& model, TissueState& s, ForkJoin& team, double h)
{
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

struct Advanced {
    bool exploded = false;    // a NaN, or a node faster than options.max_speed
    double max_speed2 = 0;    // the fastest node's squared speed [mm^2/s^2]
};

// x += h v, fixed nodes held still.
Advanced advance(const CompiledModel& model, TissueState& s, ForkJoin& team, double h)
{
    const double limit2 = model.options.max_speed * model.options.max_speed;
    std::array<Advanced, ForkJoin::kMaxParts> parts{};
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(model.grid, part, team.parts());
        Advanced& a = parts[std::size_t(part)];
        for (std::size_t i = begin; i < end; ++i) {
            auto v = s.v.segment<3>(3 * Eigen::Index(i));
            if (model.fixed(i)) v.setZero();
            auto x = s.x.segment<3>(3 * Eigen::Index(i));
            x += h * v;
            const double v2 = v.squaredNorm();
            if (!(v2 <= limit2) || !x.allFinite()) a.exploded = true;  // (a NaN fails every comparison)
            a.max_speed2 = std::max(a.max_speed2, v2);
        }
    });
    Advanced all;
    for (int part = 0; part < team.parts(); ++part) {
        all.exploded = all.exploded || parts[std::size_t(part)].exploded;
        all.max_speed2 = std::max(all.max_speed2, parts[std::size_t(part)].max_speed2);
    }
    return all;
}

// Whether the probe at `now` is still where it was at `then` (PhysicsOptions::sleep_probe_mm), and
// all but at rest.
bool probe_still(const CompiledModel& model, const contact::ProbeState& now, const contact::ProbeState& then)
{
    const PhysicsOptions& o = model.options;
    if (now.active != then.active) return false;
    if (!now.active) return true;  // no probe, no contact: where it is does not matter
    // a turn by a small angle a moves the face's corners by about a times its half diagonal
    const double half_diagonal = 0.5 * std::hypot(model.probe.face_width, model.probe.face_thickness);
    const double turn = 2.0 * (then.orientation.conjugate() * now.orientation).vec().norm();
    return (now.position - then.position).norm() + turn * half_diagonal <= o.sleep_probe_mm && now.velocity.norm() <= o.sleep_speed;
}

// Whether the probe touches no skin at the state's positions (the contact stage's own test; its
// contacts and forces land in the state's, which a step that goes on computes anew).
bool probe_clear(const CompiledModel& model, TissueState& s)
{
    return contact::collide(model.probe, model.penalty, s.probe, model.surface, s.x, s.v, s.contacts, s.force) == 0;
}

// Whether the tissue sleeps through this step: still for options.sleep_after under the same load,
// and either under a probe still where it was, or with nothing touching it and the probe still
// clear of the skin wherever it has gone (a lifted probe carried to the next station: the tissue
// at rest, untouched, stays so). The clear test is the contact stage's, a few per cent of a step.
bool sleeps(const CompiledModel& model, TissueState& s)
{
    const PhysicsOptions& o = model.options;
    if (!(o.sleep_after > 0 && s.still_for >= o.sleep_after && s.external == s.still_external)) return false;
    if (probe_still(model, s.probe, s.still_probe)) return true;
    return s.last.contacts == 0 && probe_clear(model, s);
}

// After a step: how long the tissue has been still, under the same load and the probe it was still
// under (or none touching it: where an untouching probe goes does not matter).
void track_stillness(const CompiledModel& model, TissueState& s, double max_speed2, double h)
{
    const double v = model.options.sleep_speed;
    const bool same_load = s.external == s.still_external;
    if (max_speed2 <= v * v && same_load && (s.last.contacts == 0 || probe_still(model, s.probe, s.still_probe))) {
        s.still_for += h;
        return;
    }
    s.still_for = 0;
    s.still_probe = s.probe;
    if (!same_load) s.still_external = s.external;  // (the size is the state's: no allocation; not every moving step)
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

void step(const CompiledModel& model, TissueState& s, ForkJoin& team) { step(model, s, team, 1); }

void step(const CompiledModel& model, TissueState& s, ForkJoin& team, int stride)
{
    check_wiring(model, s, team);
    if (stride < 1) throw std::invalid_argument("physics step: a stride of " + std::to_string(stride) + " time steps");
    const PhysicsOptions& options = model.options;
    const double h = options.time_step * stride;
    const bool relinearise = options.jacobian == JacobianMode::updated || !s.constant_jacobian_ready;
    if (sleeps(model, s)) {
        if (!s.last.asleep) s.v.setZero();  // at rest, as it falls asleep (as Box2D's bodies do)
        s.time += h;
        s.steps += stride;
        s.last.asleep = true;
        s.last.cg_iterations = 0;  // the contacts and the probe's force stay as they were
        return;
    }
    s.last.asleep = false;

    // 1-2: contact and forces (the contact stage adds its penalty forces after the internal ones)
    accumulate_forces(model, s, team, relinearise);
    s.constant_jacobian_ready = true;
    s.last.contacts = contact::collide(model.probe, model.penalty, s.probe, model.surface, s.x, s.v, s.contacts, s.force);
    s.last.probe_force_N = s.contacts.total_force;

    // 3: integrate
    if (options.integrator == Integrator::implicit_euler) {
        contact::add_contact_stiffness_product(s.contacts, s.v, s.stiffness_v);
        right_hand_side(model, s, team, h);
        prepare_system(model, s, s.system, team, h);
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
    const Advanced advanced = advance(model, s, team, h);
    s.time += h;
    s.steps += stride;
    if (advanced.exploded) {
        reset_to_rest(model, s);
        ++s.resets;
    }
    else
        track_stillness(model, s, advanced.max_speed2, h);
}

}  // namespace echosim::physics

#include "physics/step.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "physics/cg.hpp"
#include "physics/forces.hpp"
#include "physics/grid_system.hpp"

namespace echosim::physics {
namespace {

// The right-hand side h (f - h K v), zero at fixed nodes, into the solver's planes.
void right_hand_side(TissueState& s, double h)
{
    const std::size_t n = s.grid.n;
    float* rhs = s.cg.rhs.data();
    s.team->run([&](int part) {
        const auto [begin, end] = part_nodes(s.grid, part, s.team->parts());
        for (std::size_t i = begin; i < end; ++i)
            for (std::size_t c = 0; c < 3; ++c)
                rhs[c * n + i] = s.fixed[i] ? 0.0f : float(h * (s.force[Eigen::Index(3 * i + c)] - h * s.stiffness_v[Eigen::Index(3 * i + c)]));
    });
}

// v += dv, from the solver's planes.
void add_velocity_change(TissueState& s)
{
    s.team->run([&](int part) {
        const auto [begin, end] = part_nodes(s.grid, part, s.team->parts());
        add_planes_to(s.cg.dv.data(), s.grid.n, s.v.data(), begin, end);
    });
}

// x += h v, fixed nodes held still; true if a node has exploded (a NaN, or faster than
// options.max_speed).
bool advance(const PhysicsOptions& options, TissueState& s, double h)
{
    const double limit2 = options.max_speed * options.max_speed;
    std::array<std::uint8_t, ForkJoin::kMaxParts> exploded{};
    s.team->run([&](int part) {
        const auto [begin, end] = part_nodes(s.grid, part, s.team->parts());
        for (std::size_t i = begin; i < end; ++i) {
            auto v = s.v.segment<3>(3 * Eigen::Index(i));
            if (s.fixed[i]) v.setZero();
            auto x = s.x.segment<3>(3 * Eigen::Index(i));
            x += h * v;
            if (!(v.squaredNorm() <= limit2) || !x.allFinite()) exploded[std::size_t(part)] = 1;  // (a NaN fails every comparison)
        }
    });
    return std::any_of(exploded.begin(), exploded.end(), [](std::uint8_t e) { return e != 0; });
}

}  // namespace

Scene make_scene(const tissue::TissueModel& model)
{
    Scene scene;
    Eigen::VectorXd rest(Eigen::Index(3 * model.node_count()));
    for (std::size_t i = 0; i < model.node_count(); ++i)
        rest.segment<3>(3 * Eigen::Index(i)) = Eigen::Vector3d(model.positions[i].x, model.positions[i].y, model.positions[i].z);
    scene.surface = contact::make_patch_surface(model.rows, model.cols, rest);
    return scene;
}

void step(const tissue::TissueModel& model, const PhysicsOptions& options, const Scene& scene, TissueState& s)
{
    const double h = options.time_step;
    const bool relinearise = options.jacobian == JacobianMode::updated || !s.constant_jacobian_ready;

    // 1-2: contact and forces (the contact stage adds its penalty forces after the internal ones)
    accumulate_forces(model, options, s, relinearise);
    s.constant_jacobian_ready = true;
    s.last.contacts = contact::collide(scene.probe, scene.penalty, s.probe, scene.surface, s.x, s.v, s.contacts, s.force);
    s.last.probe_force_N = s.contacts.total_force;

    // 3: integrate
    if (options.integrator == Integrator::implicit_euler) {
        contact::add_contact_stiffness_product(s.contacts, s.v, s.stiffness_v);
        right_hand_side(s, h);
        prepare_system(model, scene.penalty, s, h, s.system, *s.team);
        const CgResult cg = conjugate_gradient(options, s.grid, s.system, s.cg, *s.team);
        s.last.cg_iterations = cg.iterations;
        s.last.cg_residual = cg.relative_residual;
        if (cg.finite) add_velocity_change(s);
        else s.v.setConstant(std::nan(""));  // the guard below resets and counts it
    } else {
        for (std::size_t i = 0; i < model.node_count(); ++i)
            s.v.segment<3>(3 * Eigen::Index(i)) += h * s.inv_mass_scaled[i] * s.force.segment<3>(3 * Eigen::Index(i));
        s.last.cg_iterations = 0;
    }

    // 4: positions, and the guard
    const bool exploded = advance(options, s, h);
    s.time += h;
    ++s.steps;
    if (exploded) {
        reset_to_rest(s);
        ++s.resets;
    }
}

}  // namespace echosim::physics

#include "physics/step.hpp"

#include <cmath>

#include "physics/cg.hpp"
#include "physics/forces.hpp"
#include "physics/system_product.hpp"

namespace echosim::physics {
namespace {

bool exploded(const PhysicsOptions& options, const TissueState& s)
{
    if (!s.x.allFinite() || !s.v.allFinite()) return true;
    const double limit2 = options.max_speed * options.max_speed;
    for (Eigen::Index i = 0; i < s.v.size(); i += 3)
        if (s.v.segment<3>(i).squaredNorm() > limit2) return true;
    return false;
}

void zero_fixed(const TissueState& s, Eigen::VectorXd& vec)
{
    for (std::size_t i = 0; i < s.fixed.size(); ++i)
        if (s.fixed[i]) vec.segment<3>(3 * Eigen::Index(i)).setZero();
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
        stiffness_product(model, scene.penalty, s, s.v, s.product);
        s.rhs = h * (s.force - h * s.product);
        zero_fixed(s, s.rhs);
        zero_fixed(s, s.dv);
        const CgResult cg = conjugate_gradient(model, options, scene.penalty, s, h);
        s.last.cg_iterations = cg.iterations;
        s.last.cg_residual = cg.relative_residual;
        if (!cg.finite) s.dv.setConstant(std::nan(""));  // the guard below resets and counts it
        s.v += s.dv;
    } else {
        for (std::size_t i = 0; i < model.node_count(); ++i)
            s.v.segment<3>(3 * Eigen::Index(i)) += h * s.inv_mass_scaled[i] * s.force.segment<3>(3 * Eigen::Index(i));
        s.last.cg_iterations = 0;
    }
    zero_fixed(s, s.v);
    s.x += h * s.v;
    s.time += h;
    ++s.steps;

    // 4: guard
    if (exploded(options, s)) {
        reset_to_rest(s);
        ++s.resets;
    }
}

}  // namespace echosim::physics

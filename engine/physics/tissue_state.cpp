#include "physics/tissue_state.hpp"

#include <algorithm>
#include <cmath>

#include "physics/step.hpp"

namespace echosim::physics {

TissueState make_state(const tissue::TissueModel& model, const PhysicsOptions& options, const Scene& scene)
{
    TissueState s;
    const std::size_t n = model.node_count();
    const Eigen::Index dof = Eigen::Index(3 * n);
    for (Eigen::VectorXd* v : {&s.x, &s.v, &s.rest, &s.external, &s.force, &s.stiffness_v})
        *v = Eigen::VectorXd::Zero(dof);
    s.inv_mass_scaled.resize(n);
    s.fixed.assign(model.boundary.begin(), model.boundary.end());
    s.grid = make_grid_layout(model);
    s.spring_rest = make_spring_planes(s.grid, 2);
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        s.spring_rest.plane(s.grid.spring_direction[k], 0)[s.grid.spring_first[k]] = float(model.springs[k].rest_length);
        s.spring_rest.plane(s.grid.spring_direction[k], 1)[s.grid.spring_first[k]] = 1.0f;
    }
    s.spring_linearisation = make_spring_planes(s.grid, 4);
    s.node_scratch.assign(n, 0.0);
    s.x_planes.assign(3 * n, 0.0);
    s.v_planes.assign(3 * n, 0.0);
    s.team = std::make_unique<ForkJoin>(options.threads);
    s.spring_rows.assign(std::size_t(options.threads), RowBuffers<6>(model.cols));
    s.normals.resize(n);
    s.system = make_grid_system(s.grid, s.fixed);
    s.cg = make_cg_vectors(n, model.cols, options.threads);
    for (std::size_t i = 0; i < n; ++i) {
        s.rest.segment<3>(3 * Eigen::Index(i)) = Eigen::Vector3d(model.positions[i].x, model.positions[i].y, model.positions[i].z);
        const double m = model.mass[i] * 1e-3;  // kg to N s^2/mm, the mass unit of N and mm/s^2
        s.inv_mass_scaled[i] = 1.0 / m;
        NormalLinearisation& lin = s.normals[i];
        lin.n = Eigen::Vector3d(model.normals[i].x, model.normals[i].y, model.normals[i].z).normalized();
        lin.stiffness = 1.0 / model.b[i];
        lin.damping = 2.0 * options.normal_damping_ratio * std::sqrt(m / model.b[i]);
        lin.lateral_stiffness = options.lateral_stiffness_ratio / model.b[i];
        lin.lateral_damping = 2.0 * options.normal_damping_ratio * std::sqrt(m * lin.lateral_stiffness);
    }
    s.contacts = contact::make_contact_set(scene.surface);
    s.system.contacts.reserve(s.contacts.contacts.capacity());  // so a step never grows it
    reset_to_rest(s);
    return s;
}

void reset_to_rest(TissueState& s)
{
    s.x = s.rest;
    s.v.setZero();
    std::fill(s.cg.dv.begin(), s.cg.dv.end(), 0.0f);
    s.constant_jacobian_ready = false;
}

}  // namespace echosim::physics

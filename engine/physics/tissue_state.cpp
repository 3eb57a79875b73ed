#include "physics/tissue_state.hpp"

#include <algorithm>

namespace echosim::physics {

TissueState make_state(const CompiledModel& model)
{
    TissueState s;
    const std::size_t n = model.node_count();
    const Eigen::Index dof = Eigen::Index(3 * n);
    const int parts = model.options.threads;
    for (Eigen::VectorXd* v : {&s.x, &s.v, &s.external, &s.still_external, &s.force, &s.stiffness_v}) *v = Eigen::VectorXd::Zero(dof);
    s.spring_linearisation = make_spring_planes(model.grid, 4);
    s.node_scratch.assign(n, 0.0);
    s.x_planes.assign(3 * n, 0.0);
    s.v_planes.assign(3 * n, 0.0);
    s.spring_rows.assign(std::size_t(parts), RowBuffers<6>(model.grid.cols));
    s.normal_stiffness.resize(n);
    // the rest stiffness, until a step linearises
    for (std::size_t i = 0; i < n; ++i) s.normal_stiffness[i] = 1.0 / model.tissue.b[i];
    s.system = make_grid_system(model.grid);
    s.cg = make_cg_vectors(model.grid, parts);
    s.contacts = contact::make_contact_set(model.surface);
    s.system.contacts.reserve(s.contacts.contacts.capacity());  // so a step never grows it
    reset_to_rest(model, s);
    return s;
}

void reset_to_rest(const CompiledModel& model, TissueState& s)
{
    s.x = model.rest;
    s.v.setZero();
    std::fill(s.cg.dv.begin(), s.cg.dv.end(), 0.0f);
    s.constant_jacobian_ready = false;
    s.still_for = 0;
}

}  // namespace echosim::physics

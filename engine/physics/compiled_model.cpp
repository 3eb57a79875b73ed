#include "physics/compiled_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/fork_join.hpp"

namespace echosim::physics {
namespace {

void check_size(const char* field, std::size_t size, std::size_t nodes)
{
    if (size != nodes)
        throw std::invalid_argument(std::string("tissue model: ") + field + " has " + std::to_string(size) + " entries for " +
                                    std::to_string(nodes) + " nodes");
}

}  // namespace

std::shared_ptr<const CompiledModel> compile_model(const tissue::TissueModel& model, const PhysicsOptions& options,
                                                   const contact::ProbeGeometry& probe, const contact::PenaltyLaw& penalty)
{
    const std::size_t n = model.node_count();
    check_size("normals", model.normals.size(), n);
    check_size("mass", model.mass.size(), n);
    check_size("a", model.a.size(), n);
    check_size("b", model.b.size(), n);
    check_size("boundary", model.boundary.size(), n);
    if (options.threads < 1 || options.threads > ForkJoin::kMaxParts)
        throw std::invalid_argument("physics options: threads " + std::to_string(options.threads) + " (1 to " +
                                    std::to_string(ForkJoin::kMaxParts) + ")");

    auto c = std::make_shared<CompiledModel>();
    c->tissue = model;
    c->options = options;
    c->probe = probe;
    c->penalty = penalty;
    c->grid = make_grid_layout(model);

    // the springs' rest lengths, in the grid's planes
    c->spring_rest = make_spring_planes(c->grid, 2);
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        c->spring_rest.plane(c->grid.spring_direction[k], 0)[c->grid.spring_first[k]] = float(model.springs[k].rest_length);
        c->spring_rest.plane(c->grid.spring_direction[k], 1)[c->grid.spring_first[k]] = 1.0f;
    }

    // per node: rest position, mass, the one fixed mask and the tissue column's constants
    c->rest.resize(Eigen::Index(3 * n));
    c->inv_mass_scaled.resize(n);
    c->free.resize(n);
    c->columns.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3& p = model.positions[i];
        c->rest.segment<3>(3 * Eigen::Index(i)) = Eigen::Vector3d(p.x, p.y, p.z);
        const double m = model.mass[i] * 1e-3;  // kg to N s^2/mm, the mass unit of N and mm/s^2
        c->inv_mass_scaled[i] = 1.0 / m;
        c->free[i] = model.boundary[i] ? 0.0f : 1.0f;
        TissueColumn& col = c->columns[i];
        col.n = Eigen::Vector3d(model.normals[i].x, model.normals[i].y, model.normals[i].z).normalized();
        col.damping = 2.0 * options.normal_damping_ratio * std::sqrt(m / model.b[i]);
        col.lateral_stiffness = options.lateral_stiffness_ratio / model.b[i];
        col.lateral_damping = 2.0 * options.normal_damping_ratio * std::sqrt(m * col.lateral_stiffness);
    }

    c->surface = contact::make_patch_surface(model.rows, model.cols, c->rest);
    return c;
}

}  // namespace echosim::physics

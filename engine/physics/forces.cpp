#include "physics/forces.hpp"

#include <algorithm>
#include <cmath>

#include "tissue/nonlinear_spring.hpp"

namespace echosim::physics {
namespace {

// F(c) continued linearly past the clamp; and its slope
void normal_spring(double c, double a, double b, double& force, double& slope)
{
    const double limit = kMaxCompressionFraction * tissue::spring_limit(a, b);
    if (c <= limit) {
        force = tissue::spring_force(c, a, b);
        slope = tissue::spring_stiffness(c, a, b);
        return;
    }
    slope = tissue::spring_stiffness(limit, a, b);
    force = tissue::spring_force(limit, a, b) + slope * (c - limit);
}

}  // namespace

void accumulate_forces(const tissue::TissueModel& model, const PhysicsOptions& options, TissueState& s,
                       bool update_linearisation)
{
    s.force = s.external;

    // surface spring-dampers
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const tissue::Spring& sp = model.springs[k];
        const auto xi = s.x.segment<3>(3 * Eigen::Index(sp.i)), xj = s.x.segment<3>(3 * Eigen::Index(sp.j));
        const Eigen::Vector3d d = xj - xi;
        const double len = d.norm();
        if (len < 1e-12) continue;
        const Eigen::Vector3d e = d / len;
        const double rate = e.dot(s.v.segment<3>(3 * Eigen::Index(sp.j)) - s.v.segment<3>(3 * Eigen::Index(sp.i)));
        const Eigen::Vector3d f = (model.lambda * (len - sp.rest_length) + model.mu * rate) * e;
        s.force.segment<3>(3 * Eigen::Index(sp.i)) += f;
        s.force.segment<3>(3 * Eigen::Index(sp.j)) -= f;
        if (update_linearisation) s.springs[k] = {e, std::max(0.0, 1.0 - sp.rest_length / len)};
    }

    // the tissue column under each node: the non-linear spring along the normal, shear across it
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        NormalLinearisation& lin = s.normals[i];
        const Eigen::Vector3d u = s.x.segment<3>(3 * Eigen::Index(i)) - s.rest.segment<3>(3 * Eigen::Index(i));
        const Eigen::Vector3d vel = s.v.segment<3>(3 * Eigen::Index(i));
        const double c = -lin.n.dot(u);  // compression
        double f = 0, slope = 0;
        normal_spring(c, model.a[i], model.b[i], f, slope);
        const Eigen::Vector3d lateral = u + c * lin.n, lateral_v = vel - lin.n.dot(vel) * lin.n;
        s.force.segment<3>(3 * Eigen::Index(i)) += (f - lin.damping * lin.n.dot(vel)) * lin.n - lin.lateral_stiffness * lateral -
                                                   lin.lateral_damping * lateral_v;
        s.force.segment<3>(3 * Eigen::Index(i)) += model.mass[i] * 1e-3 * options.gravity;  // kg mm/s^2 to N
        if (update_linearisation) lin.stiffness = slope;
    }
}

double potential_energy(const tissue::TissueModel& model, const TissueState& s)
{
    double e = 0;
    for (const tissue::Spring& sp : model.springs) {
        const double stretch = (s.x.segment<3>(3 * Eigen::Index(sp.j)) - s.x.segment<3>(3 * Eigen::Index(sp.i))).norm() - sp.rest_length;
        e += 0.5 * model.lambda * stretch * stretch;
    }
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const NormalLinearisation& lin = s.normals[i];
        const Eigen::Vector3d u = s.x.segment<3>(3 * Eigen::Index(i)) - s.rest.segment<3>(3 * Eigen::Index(i));
        const double c = -lin.n.dot(u);
        // integral of c / (b - a c) dc = -c/a - b/a^2 ln(1 - a c / b)
        const double a = model.a[i], b = model.b[i];
        e += a > 1e-12 ? -c / a - b / (a * a) * std::log1p(-a * c / b) : 0.5 * c * c / b;
        e += 0.5 * lin.lateral_stiffness * (u + c * lin.n).squaredNorm();
    }
    return e;
}

double kinetic_energy(const tissue::TissueModel& model, const TissueState& s)
{
    double e = 0;
    for (std::size_t i = 0; i < model.node_count(); ++i) e += 0.5 * model.mass[i] * 1e-3 * s.v.segment<3>(3 * Eigen::Index(i)).squaredNorm();
    return e;  // (kg/1000) (mm/s)^2 = N mm
}

}  // namespace echosim::physics

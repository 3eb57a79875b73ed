#include "physics/forces.hpp"

#include <algorithm>
#include <cmath>

#include "core/simd.hpp"
#include "physics/row_sweep.hpp"
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

// The surface spring-dampers' forces and K v, a row sweep over the grid: each spring computed once
// (length and direction in double, from the positions' planes), its results to both nodes.
template <bool kUpdate>
ECHOSIM_INLINE inline void spring_forces(const tissue::TissueModel& model, TissueState& s)
{
    const GridLayout& grid = s.grid;
    const std::size_t n = grid.n;
    const double lambda = model.lambda, mu = model.mu;
    const double* x = s.x_planes.data();
    const double* v = s.v_planes.data();
    auto springs = [&](int direction, std::size_t first, int count, const std::array<float*, 6>& out) ECHOSIM_INLINE {
        const std::size_t second = first + grid.offset(direction);
        const double* __restrict xi = x + first;
        const double* __restrict xj = x + second;
        const double* __restrict vi = v + first;
        const double* __restrict vj = v + second;
        const float* __restrict rest = s.spring_rest.plane(direction, 0) + first;
        const float* __restrict exists = s.spring_rest.plane(direction, 1) + first;
        float* __restrict beta = s.spring_linearisation.plane(direction, 0) + first;
        float* __restrict ex = s.spring_linearisation.plane(direction, 1) + first;
        float* __restrict ey = s.spring_linearisation.plane(direction, 2) + first;
        float* __restrict ez = s.spring_linearisation.plane(direction, 3) + first;
        float* __restrict fx = out[0];
        float* __restrict fy = out[1];
        float* __restrict fz = out[2];
        float* __restrict kx = out[3];
        float* __restrict ky = out[4];
        float* __restrict kz = out[5];
#pragma omp simd
        for (int k = 0; k < count; ++k) {
            const double dx = xj[k] - xi[k], dy = xj[n + k] - xi[n + k], dz = xj[2 * n + k] - xi[2 * n + k];
            const double len = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-12);
            const double ux = dx / len, uy = dy / len, uz = dz / len;
            if constexpr (kUpdate) {
                beta[k] = exists[k] * float(std::max(0.0, 1.0 - double(rest[k]) / len));
                ex[k] = float(exists[k] * ux);  // zero where there is no spring, so no block either
                ey[k] = float(exists[k] * uy);
                ez[k] = float(exists[k] * uz);
            }
            const double wx = vi[k] - vj[k], wy = vi[n + k] - vj[n + k], wz = vi[2 * n + k] - vj[2 * n + k];
            // f = (lambda (L - L0) + mu dL/dt) e on the first node, dL/dt = e . (v_j - v_i)
            const double f = exists[k] * (lambda * (len - double(rest[k])) - mu * (ux * wx + uy * wy + uz * wz));
            fx[k] = float(f * ux);
            fy[k] = float(f * uy);
            fz[k] = float(f * uz);
            // K_s (v_i - v_j) = lambda (beta w + (1 - beta) (e . w) e), from the (maybe constant) linearisation
            const double b = beta[k], along = (1.0 - b) * (ex[k] * wx + ey[k] * wy + ez[k] * wz);
            kx[k] = float(exists[k] * lambda * (b * wx + along * ex[k]));
            ky[k] = float(exists[k] * lambda * (b * wy + along * ey[k]));
            kz[k] = float(exists[k] * lambda * (b * wz + along * ez[k]));
        }
    };
    double* force = s.force.data();
    double* kv = s.stiffness_v.data();
    auto nodes = [&](std::size_t base, const std::array<const float*, 6>& sum) ECHOSIM_INLINE {
        for (int k = 0; k < grid.cols; ++k)
            for (std::size_t c = 0; c < 3; ++c) {
                force[3 * (base + std::size_t(k)) + c] += double(sum[c][k]);
                kv[3 * (base + std::size_t(k)) + c] = double(sum[3 + c][k]);
            }
    };
    sweep_rows(grid, 0, grid.rows, s.spring_rows, springs, nodes);
}

ECHOSIM_SIMD_CLONES void spring_forces_updating(const tissue::TissueModel& model, TissueState& s) { spring_forces<true>(model, s); }
ECHOSIM_SIMD_CLONES void spring_forces_constant(const tissue::TissueModel& model, TissueState& s) { spring_forces<false>(model, s); }

}  // namespace

void accumulate_forces(const tissue::TissueModel& model, const PhysicsOptions& options, TissueState& s,
                       bool update_linearisation)
{
    s.force = s.external;
    to_planes(s.x.data(), s.grid.n, s.x_planes.data());
    to_planes(s.v.data(), s.grid.n, s.v_planes.data());
    if (update_linearisation) spring_forces_updating(model, s);
    else spring_forces_constant(model, s);

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
        const double along_v = lin.n.dot(vel);
        s.stiffness_v.segment<3>(3 * Eigen::Index(i)) += lin.lateral_stiffness * (vel - along_v * lin.n) + lin.stiffness * along_v * lin.n;
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

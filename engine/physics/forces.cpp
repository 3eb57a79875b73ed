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

// A run of `count` springs of one direction whose first nodes are consecutive: their forces and
// K v into out[0..2] and out[3..5] (as the first node feels them), and as kMode says their
// linearisation into beta, e. Positions and velocities are plane vectors (n apart) at the first
// and second nodes.
struct SpringRun {
    const double *xi, *xj, *vi, *vj;
    std::size_t n;
    const float *rest, *exists;
    float *beta, *ex, *ey, *ez;
    std::array<float*, 6> out;
    int count;
};

// How a run treats the springs' linearisation: computes and stores it, computes it for a row another
// part of the team owns (and stores nothing), or reads the stored one (the constant Jacobian).
enum class Linearise { update_and_store, update, stored };

template <Linearise kMode>
ECHOSIM_INLINE inline void spring_run(const SpringRun& r, double lambda, double mu)
{
    const std::size_t n = r.n;
    const double* __restrict xi = r.xi;
    const double* __restrict xj = r.xj;
    const double* __restrict vi = r.vi;
    const double* __restrict vj = r.vj;
    const float* __restrict rest = r.rest;
    const float* __restrict exists = r.exists;
    float* __restrict beta = r.beta;
    float* __restrict ex = r.ex;
    float* __restrict ey = r.ey;
    float* __restrict ez = r.ez;
    float* __restrict fx = r.out[0];
    float* __restrict fy = r.out[1];
    float* __restrict fz = r.out[2];
    float* __restrict kx = r.out[3];
    float* __restrict ky = r.out[4];
    float* __restrict kz = r.out[5];
    const int count = r.count;
#pragma omp simd
    for (int k = 0; k < count; ++k) {
        const double dx = xj[k] - xi[k], dy = xj[n + k] - xi[n + k], dz = xj[2 * n + k] - xi[2 * n + k];
        const double len2 = dx * dx + dy * dy + dz * dz;
        const double len = std::sqrt(len2 > 1e-24 ? len2 : 1e-24);
        const double ux = dx / len, uy = dy / len, uz = dz / len;
        float b, e0, e1, e2;  // the linearisation: this step's, or the stored one
        if constexpr (kMode != Linearise::stored) {
            const double stretch = 1.0 - double(rest[k]) / len;
            b = exists[k] * float(0.5 * (stretch + std::abs(stretch)));  // max(0, stretch), in a form that vectorises
            e0 = exists[k] * float(ux);  // zero where there is no spring, so no block either
            e1 = exists[k] * float(uy);
            e2 = exists[k] * float(uz);
            if constexpr (kMode == Linearise::update_and_store) {
                beta[k] = b;
                ex[k] = e0;
                ey[k] = e1;
                ez[k] = e2;
            }
        } else {
            b = beta[k];
            e0 = ex[k];
            e1 = ey[k];
            e2 = ez[k];
        }
        const double wx = vi[k] - vj[k], wy = vi[n + k] - vj[n + k], wz = vi[2 * n + k] - vj[2 * n + k];
        // f = (lambda (L - L0) + mu dL/dt) e on the first node, dL/dt = e . (v_j - v_i)
        const double f = exists[k] * (lambda * (len - double(rest[k])) - mu * (ux * wx + uy * wy + uz * wz));
        fx[k] = float(f * ux);
        fy[k] = float(f * uy);
        fz[k] = float(f * uz);
        // K_s (v_i - v_j) = lambda (beta w + (1 - beta) (e . w) e)
        const double along = (1.0 - b) * (e0 * wx + e1 * wy + e2 * wz);
        kx[k] = float(lambda * (b * wx + along * e0));
        ky[k] = float(lambda * (b * wy + along * e1));
        kz[k] = float(lambda * (b * wz + along * e2));
    }
}

// cloned for the processor: a function of its own, so the vectoriser sees one plain loop
ECHOSIM_SIMD_CLONES void spring_run_storing(const SpringRun& r, double lambda, double mu)
{
    spring_run<Linearise::update_and_store>(r, lambda, mu);
}
ECHOSIM_SIMD_CLONES void spring_run_updating(const SpringRun& r, double lambda, double mu) { spring_run<Linearise::update>(r, lambda, mu); }
ECHOSIM_SIMD_CLONES void spring_run_stored(const SpringRun& r, double lambda, double mu) { spring_run<Linearise::stored>(r, lambda, mu); }

// The surface spring-dampers' forces and K v, a row sweep over the grid: each spring computed once
// (length and direction in double, from the positions' planes), its results to both nodes.
void spring_forces(const CompiledModel& model, TissueState& s, ForkJoin& team, bool update)
{
    const GridLayout& grid = model.grid;
    const double lambda = model.tissue.lambda, mu = model.tissue.mu;
    const double* x = s.x_planes.data();
    const double* v = s.v_planes.data();
    auto springs = [&](int direction, std::size_t first, int count, const std::array<float*, 6>& out, bool owned) {
        const std::size_t second = first + grid.offset(direction);
        const SpringRun run{x + first, x + second, v + first, v + second, grid.n,
                            model.spring_rest.plane(direction, 0) + first, model.spring_rest.plane(direction, 1) + first,
                            s.spring_linearisation.plane(direction, 0) + first, s.spring_linearisation.plane(direction, 1) + first,
                            s.spring_linearisation.plane(direction, 2) + first, s.spring_linearisation.plane(direction, 3) + first,
                            out, count};
        if (!update) spring_run_stored(run, lambda, mu);
        else if (owned) spring_run_storing(run, lambda, mu);
        else spring_run_updating(run, lambda, mu);
    };
    double* force = s.force.data();
    double* kv = s.stiffness_v.data();
    auto nodes = [&](std::size_t base, const std::array<const float*, 6>& sum) {
        for (int k = 0; k < grid.cols; ++k)
            for (std::size_t c = 0; c < 3; ++c) {
                force[3 * (base + std::size_t(k)) + c] += double(sum[c][k]);
                kv[3 * (base + std::size_t(k)) + c] = double(sum[3 + c][k]);
            }
    };
    team.run([&](int part) {
        const auto [begin, end] = part_rows(grid, part, team.parts());
        sweep_rows(grid, int(begin), int(end), s.spring_rows[std::size_t(part)], springs, nodes);
    });
}

}  // namespace

void accumulate_forces(const CompiledModel& model, TissueState& s, ForkJoin& team, bool update_linearisation)
{
    const GridLayout& grid = model.grid;
    const tissue::TissueModel& tissue = model.tissue;
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, team.parts());
        const auto range = Eigen::seq(3 * Eigen::Index(begin), 3 * Eigen::Index(end) - 1);
        s.force(range) = s.external(range);
        to_planes(s.x.data(), grid.n, s.x_planes.data(), begin, end);
        to_planes(s.v.data(), grid.n, s.v_planes.data(), begin, end);
    });
    spring_forces(model, s, team, update_linearisation);

    // the tissue column under each node: the non-linear spring along the normal, shear across it
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, team.parts());
        for (std::size_t i = begin; i < end; ++i) {
            const TissueColumn& col = model.columns[i];
            const Eigen::Vector3d u = s.x.segment<3>(3 * Eigen::Index(i)) - model.rest.segment<3>(3 * Eigen::Index(i));
            const Eigen::Vector3d vel = s.v.segment<3>(3 * Eigen::Index(i));
            const double c = -col.n.dot(u);  // compression
            double f = 0, slope = 0;
            normal_spring(c, tissue.a[i], tissue.b[i], f, slope);
            const Eigen::Vector3d lateral = u + c * col.n, lateral_v = vel - col.n.dot(vel) * col.n;
            s.force.segment<3>(3 * Eigen::Index(i)) += (f - col.damping * col.n.dot(vel)) * col.n - col.lateral_stiffness * lateral -
                                                       col.lateral_damping * lateral_v;
            s.force.segment<3>(3 * Eigen::Index(i)) += tissue.mass[i] * 1e-3 * model.options.gravity;  // kg mm/s^2 to N
            if (update_linearisation) s.normal_stiffness[i] = slope;
            const double along_v = col.n.dot(vel);
            s.stiffness_v.segment<3>(3 * Eigen::Index(i)) +=
                col.lateral_stiffness * (vel - along_v * col.n) + s.normal_stiffness[i] * along_v * col.n;
        }
    });
}

double potential_energy(const CompiledModel& model, const TissueState& s)
{
    const tissue::TissueModel& tissue = model.tissue;
    double e = 0;
    for (const tissue::Spring& sp : tissue.springs) {
        const double stretch = (s.x.segment<3>(3 * Eigen::Index(sp.j)) - s.x.segment<3>(3 * Eigen::Index(sp.i))).norm() - sp.rest_length;
        e += 0.5 * tissue.lambda * stretch * stretch;
    }
    for (std::size_t i = 0; i < model.node_count(); ++i) {
        const TissueColumn& col = model.columns[i];
        const Eigen::Vector3d u = s.x.segment<3>(3 * Eigen::Index(i)) - model.rest.segment<3>(3 * Eigen::Index(i));
        const double c = -col.n.dot(u);
        // integral of c / (b - a c) dc = -c/a - b/a^2 ln(1 - a c / b)
        const double a = tissue.a[i], b = tissue.b[i];
        e += a > 1e-12 ? -c / a - b / (a * a) * std::log1p(-a * c / b) : 0.5 * c * c / b;
        e += 0.5 * col.lateral_stiffness * (u + c * col.n).squaredNorm();
    }
    return e;
}

double kinetic_energy(const CompiledModel& model, const TissueState& s)
{
    double e = 0;
    for (std::size_t i = 0; i < model.node_count(); ++i)
        e += 0.5 * model.tissue.mass[i] * 1e-3 * s.v.segment<3>(3 * Eigen::Index(i)).squaredNorm();
    return e;  // (kg/1000) (mm/s)^2 = N mm
}

}  // namespace echosim::physics

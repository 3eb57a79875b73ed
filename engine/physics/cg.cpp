#include "physics/cg.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/simd.hpp"

namespace echosim::physics {
namespace {

// The fused pass over nodes [begin, end): dv += alpha d, r -= alpha Ap, z = P r (P the per-node
// inverse blocks); returns r . z, and r . r through `rr`.
ECHOSIM_SIMD_CLONES double update_and_precondition(std::size_t n, const GridSystem& g, float alpha, CgVectors& v, std::size_t begin,
                                                   std::size_t end, double& rr)
{
    const float* __restrict d = v.direction.data();
    const float* __restrict q = v.product.data();
    float* __restrict x = v.dv.data();
    float* __restrict r = v.residual.data();
    float* __restrict z = v.z.data();
    const float* __restrict p = g.inverse.data();
    double rz = 0, sum_rr = 0;
#pragma omp simd reduction(+ : rz, sum_rr)
    for (std::size_t i = begin; i < end; ++i) {
        x[i] += alpha * d[i];
        x[n + i] += alpha * d[n + i];
        x[2 * n + i] += alpha * d[2 * n + i];
        const float rx = r[i] - alpha * q[i], ry = r[n + i] - alpha * q[n + i], rzz = r[2 * n + i] - alpha * q[2 * n + i];
        r[i] = rx;
        r[n + i] = ry;
        r[2 * n + i] = rzz;
        const float zx = p[i] * rx + p[3 * n + i] * ry + p[4 * n + i] * rzz;
        const float zy = p[3 * n + i] * rx + p[n + i] * ry + p[5 * n + i] * rzz;
        const float zz = p[4 * n + i] * rx + p[5 * n + i] * ry + p[2 * n + i] * rzz;
        z[i] = zx;
        z[n + i] = zy;
        z[2 * n + i] = zz;
        rz += double(rx * zx + ry * zy + rzz * zz);
        sum_rr += double(rx * rx + ry * ry + rzz * rzz);
    }
    rr = sum_rr;
    return rz;
}

// d = z + beta d over nodes [begin, end) (in all three planes: each part keeps to its own nodes,
// so its data stay in its core's caches from pass to pass)
ECHOSIM_SIMD_CLONES void next_direction(std::size_t n, const std::vector<float>& z, float beta, std::vector<float>& d, std::size_t begin,
                                        std::size_t end)
{
    const float* __restrict pz = z.data();
    float* __restrict pd = d.data();
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = c * n + begin; i < c * n + end; ++i) pd[i] = pz[i] + beta * pd[i];
}

// r = b - q over nodes [begin, end); returns b . b there
ECHOSIM_SIMD_CLONES double initial_residual(std::size_t n, CgVectors& v, std::size_t begin, std::size_t end)
{
    const float* __restrict b = v.rhs.data();
    const float* __restrict q = v.product.data();
    float* __restrict r = v.residual.data();
    double bb = 0;
    for (std::size_t c = 0; c < 3; ++c) {
#pragma omp simd reduction(+ : bb)
        for (std::size_t i = c * n + begin; i < c * n + end; ++i) {
            r[i] = b[i] - q[i];
            bb += double(b[i]) * double(b[i]);
        }
    }
    return bb;
}

// The fused pass shared by the team; returns r . z and r . r, summed in part order.
double update(const GridLayout& grid, const GridSystem& g, float alpha, CgVectors& v, ForkJoin& team, double& rr)
{
    std::array<double, ForkJoin::kMaxParts> rz{}, sum_rr{};
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, team.parts());
        rz[std::size_t(part)] = update_and_precondition(grid.n, g, alpha, v, begin, end, sum_rr[std::size_t(part)]);
    });
    double total = 0;
    rr = 0;
    for (int part = 0; part < team.parts(); ++part) {
        total += rz[std::size_t(part)];
        rr += sum_rr[std::size_t(part)];
    }
    return total;
}

}  // namespace

CgVectors make_cg_vectors(const GridLayout& grid, int parts)
{
    CgVectors v;
    for (std::vector<float>* p : {&v.rhs, &v.dv, &v.residual, &v.z, &v.direction, &v.product}) p->assign(3 * grid.n, 0.0f);
    v.scratch = make_product_scratch(grid, parts);
    return v;
}

CgResult conjugate_gradient(const CompiledModel& model, const GridSystem& g, CgVectors& v, ForkJoin& team)
{
    const PhysicsOptions& options = model.options;
    const GridLayout& grid = model.grid;
    CgResult out;

    // r = b - A x0 from the warm start; z = P r, the first direction
    system_product(model, g, v.dv.data(), v.product.data(), v.scratch, team);
    std::array<double, ForkJoin::kMaxParts> partial{};
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, team.parts());
        partial[std::size_t(part)] = initial_residual(grid.n, v, begin, end);
    });
    double bb = 0;
    for (int part = 0; part < team.parts(); ++part) bb += partial[std::size_t(part)];
    std::fill(v.direction.begin(), v.direction.end(), 0.0f);  // (alpha 0 times a stale NaN would still be NaN)
    double rr = 0;
    double rz = update(grid, g, 0.0f, v, team, rr);  // alpha = 0: z = P r, and r . z, r . r
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, team.parts());
        next_direction(grid.n, v.z, 0.0f, v.direction, begin, end);  // d = z
    });
    const double rhs_norm = std::max(std::sqrt(bb), 1e-30);
    // the residual is a momentum (b = h f): the absolute floor on the force is h times it
    const double stop_rr = std::pow(std::max(options.cg_tolerance * rhs_norm, g.h * options.cg_absolute_tolerance_N), 2);

    for (; out.iterations < options.cg_max_iterations; ++out.iterations) {
        out.relative_residual = std::sqrt(rr) / rhs_norm;
        if (!std::isfinite(out.relative_residual)) {
            out.finite = false;
            return out;
        }
        if (rr <= stop_rr) break;
        const double pap = system_product(model, g, v.direction.data(), v.product.data(), v.scratch, team);
        if (!std::isfinite(pap)) {  // (a NaN in the preconditioner or the product would pass for convergence below)
            out.finite = false;
            return out;
        }
        if (!(pap > 0)) break;  // A is SPD: only round-off gets here, at convergence
        const double rz_next = update(grid, g, float(rz / pap), v, team, rr);
        const float beta = float(rz_next / rz);
        rz = rz_next;
        team.run([&](int part) {
            const auto [begin, end] = part_nodes(grid, part, team.parts());
            next_direction(grid.n, v.z, beta, v.direction, begin, end);
        });
    }
    out.relative_residual = std::sqrt(rr) / rhs_norm;
    return out;
}

}  // namespace echosim::physics

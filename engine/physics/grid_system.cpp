#include "physics/grid_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/simd.hpp"
#include "physics/tissue_state.hpp"

namespace echosim::physics {
namespace {

// Sums into the `inverse` planes each node's whole diagonal block but for the contacts: its own
// (mass and tissue column) and the block iso I + w w^T of each of the eight springs that touch it,
// four from the node and four reaching it (read before the node, from the zero-padded planes).
ECHOSIM_SIMD_CLONES void sum_diagonal_blocks(const GridLayout& grid, GridSystem& g, std::size_t begin, std::size_t end)
{
    const std::size_t n = grid.n;
    const float* __restrict own = g.diagonal.data();
    float* __restrict b = g.inverse.data();
    const float* __restrict iso[kSpringDirections];
    const float* __restrict wx[kSpringDirections];
    const float* __restrict wy[kSpringDirections];
    const float* __restrict wz[kSpringDirections];
    std::size_t offset[kSpringDirections];
    for (int d = 0; d < kSpringDirections; ++d) {
        iso[d] = g.springs.plane(d, 0);
        wx[d] = g.springs.plane(d, 1);
        wy[d] = g.springs.plane(d, 2);
        wz[d] = g.springs.plane(d, 3);
        offset[d] = grid.offset(d);
    }
#pragma omp simd
    for (std::size_t i = begin; i < end; ++i) {
        float xx = own[i], yy = own[n + i], zz = own[2 * n + i], xy = own[3 * n + i], xz = own[4 * n + i], yz = own[5 * n + i];
        for (int d = 0; d < kSpringDirections; ++d)
            for (int end_of_spring = 0; end_of_spring < 2; ++end_of_spring) {
                const std::ptrdiff_t at = std::ptrdiff_t(i) - (end_of_spring ? std::ptrdiff_t(offset[d]) : 0);
                const float s = iso[d][at], x = wx[d][at], y = wy[d][at], z = wz[d][at];
                xx += s + x * x;
                yy += s + y * y;
                zz += s + z * z;
                xy += x * y;
                xz += x * z;
                yz += y * z;
            }
        b[i] = xx;
        b[n + i] = yy;
        b[2 * n + i] = zz;
        b[3 * n + i] = xy;
        b[4 * n + i] = xz;
        b[5 * n + i] = yz;
    }
}

// In place over the `inverse` planes: each node's symmetric 3 x 3 block (xx yy zz xy xz yz) replaced
// by its inverse, and by zero at fixed nodes. In double: the determinant sums products of three
// entries of about 1e-9, which float would round badly.
ECHOSIM_SIMD_CLONES void invert_blocks(std::size_t n, const std::vector<float>& free_mask, GridSystem& g, std::size_t begin,
                                       std::size_t end)
{
    float* __restrict m = g.inverse.data();
    const float* __restrict free = free_mask.data();
#pragma omp simd
    for (std::size_t i = begin; i < end; ++i) {
        const double a = m[i], b = m[n + i], c = m[2 * n + i], d = m[3 * n + i], e = m[4 * n + i], f = m[5 * n + i];
        const double c00 = b * c - f * f, c01 = e * f - d * c, c02 = d * f - b * e;
        const double c11 = a * c - e * e, c12 = d * e - a * f, c22 = a * b - d * d;
        // (a select, not free / det: a fixed node's block must give zero even were it singular)
        const double inv = free[i] != 0.0f ? 1.0 / (a * c00 + d * c01 + e * c02) : 0.0;
        m[i] = float(c00 * inv);
        m[n + i] = float(c11 * inv);
        m[2 * n + i] = float(c22 * inv);
        m[3 * n + i] = float(c01 * inv);
        m[4 * n + i] = float(c02 * inv);
        m[5 * n + i] = float(c12 * inv);
    }
}

// The springs' blocks with h folded in, from the linearisation (beta, e):
// h^2 K_s + h D_s = h^2 lambda (beta I + (1 - beta) e e^T) + h mu e e^T = iso I + w w^T.
ECHOSIM_SIMD_CLONES void spring_blocks(const SpringPlanes& linearisation, double lambda, double mu, double h, SpringPlanes& out,
                                       std::size_t begin, std::size_t end)
{
    const float h2_lambda = float(h * h * lambda), h_mu = float(h * mu);
    for (int d = 0; d < kSpringDirections; ++d) {
        const float* __restrict beta = linearisation.plane(d, 0);
        const float* __restrict ex = linearisation.plane(d, 1);
        const float* __restrict ey = linearisation.plane(d, 2);
        const float* __restrict ez = linearisation.plane(d, 3);
        float* __restrict iso = out.plane(d, 0);
        float* __restrict wx = out.plane(d, 1);
        float* __restrict wy = out.plane(d, 2);
        float* __restrict wz = out.plane(d, 3);
#pragma omp simd
        for (std::size_t i = begin; i < end; ++i) {
            iso[i] = h2_lambda * beta[i];
            const float root = std::sqrt(h2_lambda * (1.0f - beta[i]) + h_mu);
            wx[i] = root * ex[i];
            wy[i] = root * ey[i];
            wz[i] = root * ez[i];
        }
    }
}

}  // namespace

GridSystem make_grid_system(const GridLayout& grid)
{
    GridSystem g;
    g.springs = make_spring_planes(grid, 4);
    g.diagonal.assign(6 * grid.n, 0.0f);
    g.inverse.assign(6 * grid.n, 0.0f);
    g.contacts.reserve(1024);
    g.contact_nodes.reserve(grid.n);
    g.contact_place.assign(grid.n, GridSystem::kNoPlace);
    return g;
}

ProductScratch make_product_scratch(const GridLayout& grid, int parts)
{
    ProductScratch s;
    s.rows.assign(std::size_t(parts), RowBuffers<3>(grid.cols));
    s.along.reserve(grid.n);
    s.sum.reserve(grid.n);
    return s;
}

void prepare_system(const CompiledModel& model, const TissueState& s, GridSystem& g, ForkJoin& team)
{
    prepare_system(model, s, g, team, model.options.time_step);
}

void prepare_system(const CompiledModel& model, const TissueState& s, GridSystem& g, ForkJoin& team, double h)
{
    const double h2 = h * h;
    g.h = h;
    const tissue::TissueModel& tissue = model.tissue;
    const GridLayout& grid = model.grid;
    const std::size_t n = grid.n;
    const int parts = team.parts();

    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, parts);
        spring_blocks(s.spring_linearisation, tissue.lambda, tissue.mu, h, g.springs, begin, end);
        // mass and the tissue column: (m + k_t) I + (k_n - k_t) n n^T, h folded into k_n and k_t
        for (std::size_t i = begin; i < end; ++i) {
            const TissueColumn& col = model.columns[i];
            const double k_n = h2 * s.normal_stiffness[i] + h * col.damping, k_t = h2 * col.lateral_stiffness + h * col.lateral_damping;
            const double iso = tissue.mass[i] * 1e-3 + k_t, along = k_n - k_t;
            const Eigen::Vector3d& nn = col.n;
            const double block[6] = {iso + along * nn.x() * nn.x(), iso + along * nn.y() * nn.y(), iso + along * nn.z() * nn.z(),
                                     along * nn.x() * nn.y(),       along * nn.x() * nn.z(),       along * nn.y() * nn.z()};
            for (int c = 0; c < 6; ++c) g.diagonal[std::size_t(c) * n + i] = float(block[c]);
        }
    });

    // contacts: (h^2 + h tau) k (w a)(w a)^T, and across the long sides h^2 k_a w^2 c c^T (a
    // stiffness with no force and no damping of its own: contact::add_contact_stiffness_product)
    const double scale = h2 + h * model.penalty.damping_time;
    const Eigen::Vector3d& ac = s.contacts.across;
    const double across[6] = {ac.x() * ac.x(), ac.y() * ac.y(), ac.z() * ac.z(), ac.x() * ac.y(), ac.x() * ac.z(), ac.y() * ac.z()};
    g.contacts.clear();
    for (std::uint32_t node : g.contact_nodes) g.contact_place[node] = GridSystem::kNoPlace;
    g.contact_nodes.clear();
    for (const contact::Contact& c : s.contacts.contacts) {
        const double root = std::sqrt(scale * c.stiffness);
        // g is zero at a fixed node, whose row of A is the identity on zero (p is zero there)
        ContactTerm term;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t node = c.nodes[k];
            term.g[k] = float(root * c.weights[int(k)]) * model.free[node];
            if (g.contact_place[node] == GridSystem::kNoPlace) {
                g.contact_place[node] = std::uint32_t(g.contact_nodes.size());
                g.contact_nodes.push_back(node);
            }
            term.nodes[k] = g.contact_place[node];
        }
        g.contacts.push_back(term);
        // across the long sides: each node's own block (contact::add_contact_stiffness_product)
        if (c.across_stiffness == 0) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t node = c.nodes[k];
            if (model.fixed(node)) continue;  // a fixed node's row is the identity
            const double w = h2 * c.across_stiffness * c.weights[int(k)] * c.weights[int(k)];
            for (std::size_t e = 0; e < 6; ++e) g.diagonal[e * n + node] += float(w * across[e]);
        }
    }
    for (int c = 0; c < 3; ++c) g.axis[std::size_t(c)] = float(s.contacts.axis[c]);

    // the block-Jacobi preconditioner: each node's whole diagonal block (its own, and every spring
    // and contact that touches it) summed into `inverse`, then inverted there
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, parts);
        sum_diagonal_blocks(grid, g, begin, end);
    });
    const float ax = g.axis[0], ay = g.axis[1], az = g.axis[2];
    const float aa[6] = {ax * ax, ay * ay, az * az, ax * ay, ax * az, ay * az};
    for (const ContactTerm& c : g.contacts)
        for (std::size_t k = 0; k < 3; ++k)
            for (std::size_t e = 0; e < 6; ++e) g.inverse[e * n + g.contact_nodes[c.nodes[k]]] += c.g[k] * c.g[k] * aa[e];
    team.run([&](int part) {
        const auto [begin, end] = part_nodes(grid, part, parts);
        invert_blocks(n, model.free, g, begin, end);
    });
}

namespace {

// A p over rows [row_begin, row_end), springs and nodes but not contacts; returns their p . out.
ECHOSIM_SIMD_CLONES double product_rows(const GridLayout& grid, const std::vector<float>& free, const GridSystem& g, const float* p,
                                        float* out, RowBuffers<3>& rows, int row_begin, int row_end)
{
    const std::size_t n = grid.n;
    const float* px = p;
    const float* py = p + n;
    const float* pz = p + 2 * n;
    float* ox = out;
    float* oy = out + n;
    float* oz = out + 2 * n;
    double pap = 0;

    // each spring's block times (p_i - p_j)
    auto springs = [&](int direction, std::size_t first, int count, const std::array<float*, 3>& b, bool) ECHOSIM_INLINE {
        const std::size_t second = first + grid.offset(direction);
        const float* __restrict iso = g.springs.plane(direction, 0) + first;
        const float* __restrict wx = g.springs.plane(direction, 1) + first;
        const float* __restrict wy = g.springs.plane(direction, 2) + first;
        const float* __restrict wz = g.springs.plane(direction, 3) + first;
        const float* __restrict xi = px + first;
        const float* __restrict yi = py + first;
        const float* __restrict zi = pz + first;
        const float* __restrict xj = px + second;
        const float* __restrict yj = py + second;
        const float* __restrict zj = pz + second;
        float* __restrict bx = b[0];
        float* __restrict by = b[1];
        float* __restrict bz = b[2];
#pragma omp simd
        for (int k = 0; k < count; ++k) {
            const float dx = xi[k] - xj[k], dy = yi[k] - yj[k], dz = zi[k] - zj[k];
            const float s = wx[k] * dx + wy[k] * dy + wz[k] * dz;
            bx[k] = iso[k] * dx + s * wx[k];
            by[k] = iso[k] * dy + s * wy[k];
            bz[k] = iso[k] * dz + s * wz[k];
        }
    };
    // plus each node's own block, masked at fixed nodes
    auto nodes = [&](std::size_t base, const std::array<const float*, 3>& sum) ECHOSIM_INLINE {
        const float* __restrict d0 = g.diagonal.data() + base;
        const float* __restrict d1 = d0 + n;
        const float* __restrict d2 = d0 + 2 * n;
        const float* __restrict d3 = d0 + 3 * n;
        const float* __restrict d4 = d0 + 4 * n;
        const float* __restrict d5 = d0 + 5 * n;
        const float* __restrict mask = free.data() + base;
        const float* __restrict rx = px + base;
        const float* __restrict ry = py + base;
        const float* __restrict rz = pz + base;
        const float* __restrict sx = sum[0];
        const float* __restrict sy = sum[1];
        const float* __restrict sz = sum[2];
        float* __restrict wx = ox + base;
        float* __restrict wy = oy + base;
        float* __restrict wz = oz + base;
        double row_pap = 0;
#pragma omp simd reduction(+ : row_pap)
        for (int k = 0; k < grid.cols; ++k) {
            const float x = mask[k] * (sx[k] + d0[k] * rx[k] + d3[k] * ry[k] + d4[k] * rz[k]);
            const float y = mask[k] * (sy[k] + d3[k] * rx[k] + d1[k] * ry[k] + d5[k] * rz[k]);
            const float z = mask[k] * (sz[k] + d4[k] * rx[k] + d5[k] * ry[k] + d2[k] * rz[k]);
            wx[k] = x;
            wy[k] = y;
            wz[k] = z;
            row_pap += double(rx[k] * x + ry[k] * y + rz[k] * z);
        }
        pap += row_pap;
    };
    sweep_rows(grid, row_begin, row_end, rows, springs, nodes);
    return pap;
}

}  // namespace

double system_product(const CompiledModel& model, const GridSystem& g, const float* p, float* out, ProductScratch& scratch, ForkJoin& team)
{
    const GridLayout& grid = model.grid;
    std::array<double, ForkJoin::kMaxParts> partial{};
    team.run([&](int part) {
        const auto [begin, end] = part_rows(grid, part, team.parts());
        partial[std::size_t(part)] = product_rows(grid, model.free, g, p, out, scratch.rows[std::size_t(part)], int(begin), int(end));
    });
    double pap = 0;
    for (int part = 0; part < team.parts(); ++part) pap += partial[std::size_t(part)];
    // the probe's contacts: rank-one blocks along the axis over each sample's triangle, gathered
    // from and scattered to the listed nodes once each
    const std::size_t n = grid.n;
    const float ax = g.axis[0], ay = g.axis[1], az = g.axis[2];
    scratch.along.resize(g.contact_nodes.size());  // within the capacity reserved
    scratch.sum.resize(g.contact_nodes.size());
    float* __restrict along = scratch.along.data();
    float* __restrict sum = scratch.sum.data();
    for (std::size_t j = 0; j < g.contact_nodes.size(); ++j) {
        const std::size_t m = g.contact_nodes[j];
        along[j] = ax * p[m] + ay * p[n + m] + az * p[2 * n + m];
        sum[j] = 0;
    }
    double contact_pap = 0;
    for (const ContactTerm& c : g.contacts) {
        const float t = c.g[0] * along[c.nodes[0]] + c.g[1] * along[c.nodes[1]] + c.g[2] * along[c.nodes[2]];
        for (std::size_t k = 0; k < 3; ++k) sum[c.nodes[k]] += c.g[k] * t;  // zero at a fixed node: its g is
        contact_pap += double(t) * double(t);  // p . K_c p
    }
    for (std::size_t j = 0; j < g.contact_nodes.size(); ++j) {
        const std::size_t m = g.contact_nodes[j];
        out[m] += sum[j] * ax;
        out[n + m] += sum[j] * ay;
        out[2 * n + m] += sum[j] * az;
    }
    return pap + contact_pap;
}

}  // namespace echosim::physics

// Stage 2: the implicit step's matrix
//     A = M + h D + h^2 K        (the probe's contact included in D and K)
// with M the masses, D the damping and K the stiffness (both positive semi-definite: the negated
// force Jacobians), in the grid's stencil form (grid_layout.hpp): per node its own 3 x 3 block (mass
// and tissue column), per spring a block iso I + w w^T, per contact sample a rank-one block along
// the probe axis. The solver's vectors are plane vectors of floats, so the product, a 9-point
// stencil of 3 x 3 blocks, runs as a row sweep (row_sweep.hpp) whose loops vectorise. The
// coefficients are rebuilt from the force stage's linearisation once per step, with h folded in.
// Units: A's blocks in N s^2/mm (a mass: dv in mm/s times A gives an impulse h f in N s).
// Floats, not doubles: half the memory traffic and twice the lanes; conjugate gradient stops at a
// relative residual of 1e-4, far above float round-off (a test bounds the product's error against
// a double-precision assembled matrix).
//
// Rows of fixed nodes are the identity on zero (Baraff and Witkin's filter): the right-hand side,
// the preconditioner and so every search direction are zero there, and the product is masked by
// the compiled model's fixed mask (CompiledModel::free).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "contact/probe_contact.hpp"
#include "core/fork_join.hpp"
#include "physics/compiled_model.hpp"
#include "physics/grid_layout.hpp"
#include "physics/row_sweep.hpp"

namespace echosim::physics {

struct TissueState;

// One contact sample as the product sees it: K_c p = (sum_k g_k a.p_k) g_m a at node m, g_k the
// square root of the contact's stiffness (with h folded in) times its barycentric weight, and zero
// at a fixed node [sqrt(N s^2/mm)]. Its nodes are named by their place in GridSystem::contact_nodes.
struct ContactTerm {
    std::array<std::uint32_t, 3> nodes{};
    std::array<float, 3> g{};
};

struct GridSystem {
    SpringPlanes springs;  // per direction: iso, w.x, w.y, w.z
    // per node, the symmetric block of M + the tissue column: planes xx, yy, zz, xy, xz, yz
    std::vector<float> diagonal;
    // block-Jacobi preconditioner: per node the inverse of A's whole diagonal block, same planes;
    // zero at fixed nodes
    std::vector<float> inverse;
    std::array<float, 3> axis{0, 1, 0};  // the probe axis the contacts push along
    double h = 0;                        // the step the system was prepared for [s]
    std::vector<ContactTerm> contacts;
    // The nodes the contacts touch, each once: the samples share their nodes (some 1,300 samples,
    // a third as many nodes), so the product reads each node's p and adds to its row once, from a
    // compact list, rather than three times a sample at scattered places. contact_place[node] is
    // the node's index in the list, or kNoPlace. Sized once (make_grid_system): a step allocates
    // nothing.
    static constexpr std::uint32_t kNoPlace = 0xffffffffu;
    std::vector<std::uint32_t> contact_nodes;
    std::vector<std::uint32_t> contact_place;
};

// The product's working memory.
struct ProductScratch {
    std::vector<RowBuffers<3>> rows;  // one per part of the team
    std::vector<float> along, sum;    // per contact node: a . p, and the contacts' sum for its row
};

ProductScratch make_product_scratch(const GridLayout& grid, int parts);

GridSystem make_grid_system(const GridLayout& grid);

// Rebuilds the coefficients, the contact terms and the preconditioner for a step of
// model.options.time_step, from the force stage's linearisation (state.spring_linearisation,
// state.normal_stiffness) and state.contacts. The work is shared by `team`.
void prepare_system(const CompiledModel& model, const TissueState& state, GridSystem& system, ForkJoin& team);
// The same for a step of h seconds (a stride of several time steps: PhysicsOptions::clear_stride).
void prepare_system(const CompiledModel& model, const TissueState& state, GridSystem& system, ForkJoin& team, double h);

// out = A p over plane vectors of 3n floats; returns p . out (accumulated in double). The rows are
// shared by `team`, each part with its row buffers scratch.rows[part].
double system_product(const CompiledModel& model, const GridSystem& system, const float* p, float* out, ProductScratch& scratch,
                      ForkJoin& team);

}  // namespace echosim::physics

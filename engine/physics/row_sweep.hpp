// The grid's springs visited a row at a time (grid_layout.hpp), for the stages that add each
// spring's contribution to both of its nodes (forces, the system product): each spring is computed
// once and each node written once, in loops without scatter that vectorise. A row's springs go
// into row buffers, each at its first node's column + 1: the east springs of this row, and the
// downward (south, south-east, south-west) springs of this row and of the row before. A node's sum
// is then what its own springs give minus what the springs that reach it give.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "core/simd.hpp"
#include "physics/grid_layout.hpp"

namespace echosim::physics {

// C components per spring (3 for a vector, 6 for two).
template <int C>
struct RowBuffers {
    // the east springs, the downward springs (3) of this row and of the row before (3), the sums
    static constexpr int kEastRow = 0, kDownward = 1, kDownwardBefore = 4, kSum = 7, kCount = 8;
    int cols = 0;
    std::vector<float> data;

    RowBuffers() = default;
    explicit RowBuffers(int columns) : cols(columns), data(std::size_t(C * kCount) * std::size_t(columns + 2), 0.0f) {}
    float* at(int which, int component) { return data.data() + std::size_t(which * C + component) * std::size_t(cols + 2); }
};

// springs(direction, first, count, out, owned): writes the contributions of `count` springs of
// `direction` whose first nodes are first, first + 1, ..., component c of spring k to out[c][k] (as
// the first node feels it; the second feels its negative). `owned` is false for the row before
// row_begin, which the sweep recomputes for its downward springs: another range owns that row, so
// the callback must not write anything of its springs but `out`.
// nodes(base, sum): sum[c][k] is the total on node base + k, for the row's cols nodes.
// Rows [row_begin, row_end) are visited, so disjoint ranges of rows can be swept at once.
template <int C, class Springs, class Nodes>
ECHOSIM_INLINE inline void sweep_rows(const GridLayout& g, int row_begin, int row_end, RowBuffers<C>& b, Springs&& springs, Nodes&& nodes)
{
    using Row = RowBuffers<C>;
    const int cols = g.cols;
    std::fill(b.data.begin(), b.data.end(), 0.0f);
    auto out = [&](int which, int at) ECHOSIM_INLINE {
        std::array<float*, C> p;
        for (int c = 0; c < C; ++c) p[std::size_t(c)] = b.at(which, c) + at;
        return p;
    };
    auto downward = [&](int row, int which, bool owned) ECHOSIM_INLINE {
        const std::size_t base = std::size_t(row) * std::size_t(cols);
        springs(kSouth, base, cols, out(which + 0, 1), owned);
        springs(kSouthEast, base, cols - 1, out(which + 1, 1), owned);
        springs(kSouthWest, base + 1, cols - 1, out(which + 2, 2), owned);
    };
    int down = Row::kDownward, before = Row::kDownwardBefore;
    if (row_begin > 0) downward(row_begin - 1, before, false);
    for (int r = row_begin; r < row_end; ++r) {
        const std::size_t base = std::size_t(r) * std::size_t(cols);
        springs(kEast, base, cols - 1, out(Row::kEastRow, 1), true);
        if (r + 1 < g.rows) {
            downward(r, down, true);
        } else {
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < C; ++c) std::fill_n(b.at(down + k, c), cols + 2, 0.0f);
        }
        std::array<const float*, C> sum;
        for (int c = 0; c < C; ++c) {
            const float* __restrict e = b.at(Row::kEastRow, c);
            const float* __restrict s = b.at(down + 0, c);
            const float* __restrict se = b.at(down + 1, c);
            const float* __restrict sw = b.at(down + 2, c);
            const float* __restrict bs = b.at(before + 0, c);
            const float* __restrict bse = b.at(before + 1, c);
            const float* __restrict bsw = b.at(before + 2, c);
            float* __restrict o = b.at(Row::kSum, c);
#pragma omp simd
            for (int k = 0; k < cols; ++k) o[k] = e[k + 1] - e[k] + s[k + 1] + se[k + 1] + sw[k + 1] - bs[k + 1] - bse[k] - bsw[k + 2];
            sum[std::size_t(c)] = o;
        }
        nodes(base, sum);
        std::swap(down, before);
    }
}

}  // namespace echosim::physics

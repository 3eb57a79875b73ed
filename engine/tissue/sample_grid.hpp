// Where the force-displacement measurements are taken (paper §3.1: 64 points regularly spread over
// the exam area): an 8 x 8 grid over the exam patch, at the centres of its cells. Point p = i * 8 + j
// sits at patch coordinates (u, v) = ((i + 0.5) / 8, (j + 0.5) / 8): u along the thigh from superior,
// v around it from medial towards anterior (scene::LegModel::patch_point).
#pragma once

namespace echosim::tissue {

struct SampleGrid {
    static constexpr int rows = 8;
    static constexpr int cols = 8;
    static constexpr int count = rows * cols;

    static constexpr double u(int row) { return (row + 0.5) / rows; }
    static constexpr double v(int col) { return (col + 0.5) / cols; }
    static constexpr int index(int row, int col) { return row * cols + col; }
    static constexpr int row_of(int point) { return point / cols; }
    static constexpr int col_of(int point) { return point % cols; }
};

}  // namespace echosim::tissue

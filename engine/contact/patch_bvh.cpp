#include "contact/patch_bvh.hpp"

namespace echosim::contact {

namespace {
constexpr int kLeafCells = 4;
}

GridBvh::GridBvh(int rows, int cols) : rows_(rows), cols_(cols)
{
    nodes_.reserve(std::size_t(4 * (rows - 1) * (cols - 1) / kLeafCells + 8));
    if (rows > 1 && cols > 1) build(0, rows - 1, 0, cols - 1);
    stack_.reserve(64);
}

int GridBvh::build(int r0, int r1, int c0, int c1)
{
    const int index = int(nodes_.size());
    nodes_.push_back({r0, r1, c0, c1});
    if ((r1 - r0) * (c1 - c0) <= kLeafCells) return index;
    int left, right;
    if (r1 - r0 >= c1 - c0) {
        const int mid = (r0 + r1) / 2;
        left = build(r0, mid, c0, c1);
        right = build(mid, r1, c0, c1);
    } else {
        const int mid = (c0 + c1) / 2;
        left = build(r0, r1, c0, mid);
        right = build(r0, r1, mid, c1);
    }
    nodes_[std::size_t(index)].left = left;
    nodes_[std::size_t(index)].right = right;
    return index;
}

void GridBvh::refit(const Eigen::VectorXd& x)
{
    if (!nodes_.empty()) refit(0, x);
}

void GridBvh::refit(int index, const Eigen::VectorXd& x)
{
    Node& n = nodes_[std::size_t(index)];
    n.box = Aabb{};
    if (n.left < 0) {
        // a leaf: the nodes at the corners of its cells
        for (int r = n.r0; r <= n.r1; ++r)
            for (int c = n.c0; c <= n.c1; ++c) n.box.grow(x.segment<3>(3 * Eigen::Index(r * cols_ + c)));
        return;
    }
    refit(n.left, x);
    refit(n.right, x);
    const Node &a = nodes_[std::size_t(n.left)], &b = nodes_[std::size_t(n.right)];
    n.box.lo = a.box.lo.cwiseMin(b.box.lo);
    n.box.hi = a.box.hi.cwiseMax(b.box.hi);
}

void GridBvh::query(const Aabb& box, const Eigen::VectorXd& x, std::vector<std::uint32_t>& cells) const
{
    if (nodes_.empty()) return;
    stack_.clear();
    stack_.push_back(0);
    while (!stack_.empty()) {
        const Node& n = nodes_[std::size_t(stack_.back())];
        stack_.pop_back();
        if (!n.box.overlaps(box)) continue;
        if (n.left < 0) {
            for (int r = n.r0; r < n.r1; ++r)
                for (int c = n.c0; c < n.c1; ++c) {
                    Aabb cell;
                    for (int k : {r * cols_ + c, r * cols_ + c + 1, (r + 1) * cols_ + c, (r + 1) * cols_ + c + 1})
                        cell.grow(x.segment<3>(3 * Eigen::Index(k)));
                    if (cell.overlaps(box)) cells.push_back(std::uint32_t(r * (cols_ - 1) + c));
                }
            continue;
        }
        stack_.push_back(n.left);
        stack_.push_back(n.right);
    }
}

}  // namespace echosim::contact

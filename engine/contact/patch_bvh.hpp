// The broad phase of the contact: a bounding-volume hierarchy over the cells of the patch's grid,
// built once from the grid's shape (each node a rectangle of cells, split along its longer side)
// and refitted from the node positions every step, since the patch deforms but keeps its topology.
// A query returns the cells whose refitted box meets a given axis-aligned box.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace echosim::contact {

struct Aabb {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300);
    Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1e300);
    void grow(const Eigen::Vector3d& p)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    bool overlaps(const Aabb& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

class GridBvh {
public:
    // A grid of rows x cols nodes, (rows - 1) x (cols - 1) cells; node (r, c) is r * cols + c.
    GridBvh(int rows, int cols);

    void refit(const Eigen::VectorXd& x);  // x: 3 per node
    // Appends to `cells` (index r * (cols - 1) + c) every cell whose own box (of its four nodes in
    // `x`, the positions of the last refit) overlaps `box`.
    void query(const Aabb& box, const Eigen::VectorXd& x, std::vector<std::uint32_t>& cells) const;

    std::size_t node_count() const { return nodes_.size(); }

private:
    struct Node {
        int r0, r1, c0, c1;  // cell range [r0, r1) x [c0, c1)
        int left = -1, right = -1;
        Aabb box;
    };
    int build(int r0, int r1, int c0, int c1);
    void refit(int index, const Eigen::VectorXd& x);

    int rows_, cols_;
    std::vector<Node> nodes_;
    mutable std::vector<int> stack_;
};

}  // namespace echosim::contact

#include "contact/probe_contact.hpp"

#include <algorithm>
#include <cmath>

namespace echosim::contact {
namespace {

// Calls visit(wb, wc) for the k^2 sample points of a triangle subdivided k times: the centroids of
// its sub-triangles, in barycentric coordinates of vertices b and c.
template <class Visit>
void for_each_sample(int k, Visit&& visit)
{
    const double inv = 1.0 / k;
    for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j) {
            visit((i + 1.0 / 3.0) * inv, (j + 1.0 / 3.0) * inv);                        // upward
            if (i + j + 2 <= k) visit((i + 2.0 / 3.0) * inv, (j + 2.0 / 3.0) * inv);  // downward
        }
}

Eigen::Vector3d node(const Eigen::VectorXd& x, std::uint32_t i) { return x.segment<3>(3 * Eigen::Index(i)); }

}  // namespace

PatchSurface make_patch_surface(int rows, int cols, const Eigen::VectorXd& rest, double spacing)
{
    PatchSurface s;
    s.rows = rows;
    s.cols = cols;
    for (int r = 0; r + 1 < rows; ++r)
        for (int c = 0; c + 1 < cols; ++c) {
            const auto a = std::uint32_t(r * cols + c), b = a + 1, d = a + std::uint32_t(cols), e = d + 1;
            s.triangles.push_back({a, d, e});
            s.triangles.push_back({a, e, b});
        }
    for (const auto& t : s.triangles) {
        const Eigen::Vector3d p0 = node(rest, t[0]), p1 = node(rest, t[1]), p2 = node(rest, t[2]);
        const double longest = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
        const int k = std::clamp(int(std::ceil(longest / spacing)), 1, 255);
        s.subdivision.push_back(std::uint8_t(k));
        s.sample_area.push_back(0.5 * (p1 - p0).cross(p2 - p0).norm() / double(k * k));
    }
    return s;
}

ProbeDepth probe_depth(const ProbeGeometry& g, const Eigen::Vector3d& local)
{
    // the probe's profile along its array (x, y) as a core rectangle grown by the radius (a
    // signed distance); across the array (z) the face ends where it ends
    const Eigen::Vector2d half(0.5 * g.face_width, 0.5 * g.body_depth);
    const double r = std::clamp(g.edge_radius, 0.0, half.minCoeff());
    // most samples: under the flat of the face, nearer it than an end or the back (the general
    // path below gives the same; this one saves some 8 % of a 2,500-node step)
    const double to_end = half.x() - std::abs(local.x());
    if (to_end >= r && -local.y() <= std::min(to_end, half.y())) return {-local.y(), Eigen::Vector3d::UnitY(), 0.0};
    const Eigen::Vector2d d(local.x(), local.y() + half.y());  // from the box's centre
    const Eigen::Vector2d q = d.cwiseAbs() - (half - Eigen::Vector2d::Constant(r));
    const Eigen::Vector2d beyond = q.cwiseMax(0.0);
    const double out = beyond.norm();
    ProbeDepth depth;
    if (out > 0.0) {
        depth.penetration = r - out;
        const Eigen::Vector2d n = beyond.cwiseProduct(d.cwiseSign()) / out;
        depth.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
        if (beyond.x() > 0.0 && beyond.y() > 0.0) depth.turn = 1.0 / out;  // over a rounded end
    } else {  // within the core: the nearest face's
        const bool side = q.x() > q.y();
        depth.penetration = r - std::max(q.x(), q.y());
        depth.normal = side ? Eigen::Vector3d(d.x() < 0.0 ? -1.0 : 1.0, 0.0, 0.0) : Eigen::Vector3d(0.0, d.y() < 0.0 ? -1.0 : 1.0, 0.0);
    }
    return depth;
}

ContactSet make_contact_set(const PatchSurface& surface)
{
    ContactSet set;
    set.bvh = GridBvh(surface.rows, surface.cols);
    std::size_t samples = 0;
    for (std::uint8_t k : surface.subdivision) samples += std::size_t(k) * k;
    set.contacts.reserve(samples);
    set.cells.reserve(surface.triangles.size() / 2 + 1);
    return set;
}

int collide(const ProbeGeometry& g, const PenaltyLaw& law, const ProbeState& probe, const PatchSurface& surface,
            const Eigen::VectorXd& x, const Eigen::VectorXd& v, ContactSet& set, Eigen::VectorXd& force)
{
    set.contacts.clear();
    set.total_force = 0;
    if (!probe.active) return 0;
    const Eigen::Matrix3d to_world = probe.orientation.toRotationMatrix();
    const Eigen::Matrix3d to_local = to_world.transpose();
    set.axis = to_world.col(1);
    set.across = to_world.col(2);
    const double hw = g.face_width / 2, ht = g.face_thickness / 2;

    // broad phase: the cells whose boxes meet the probe box's world-space bounds
    Aabb box;
    for (double bx : {-hw, hw})
        for (double by : {-g.body_depth, 0.0})
            for (double bz : {-ht, ht}) box.grow(probe.position + to_world * Eigen::Vector3d(bx, by, bz));
    set.bvh.refit(x);
    set.cells.clear();
    set.bvh.query(box, x, set.cells);

    // narrow phase: the material samples of those cells' triangles that lie inside the box
    for (std::uint32_t cell : set.cells)
        for (std::uint32_t t = 2 * cell; t < 2 * cell + 2; ++t) {
            const auto& tri = surface.triangles[t];
            const Eigen::Vector3d a = to_local * (node(x, tri[0]) - probe.position);
            const Eigen::Vector3d b = to_local * (node(x, tri[1]) - probe.position);
            const Eigen::Vector3d c = to_local * (node(x, tri[2]) - probe.position);
            if (std::min({a.y(), b.y(), c.y()}) >= 0.0) continue;  // wholly beyond the face
            // wholly beside the face (its samples, inside the triangle, are too): the skin around a
            // pressed probe lies in front of its face and fills the broad phase's box
            if (std::min({a.x(), b.x(), c.x()}) > hw || std::max({a.x(), b.x(), c.x()}) < -hw) continue;
            if (std::min({a.z(), b.z(), c.z()}) > ht || std::max({a.z(), b.z(), c.z()}) < -ht) continue;
            const double area = surface.sample_area[t];
            for_each_sample(surface.subdivision[t], [&](double wb, double wc) {
                const double wa = 1.0 - wb - wc;
                const Eigen::Vector3d p = wa * a + wb * b + wc * c;
                if (p.y() >= 0.0 || p.y() < -g.body_depth || std::abs(p.x()) > hw || std::abs(p.z()) > ht) return;
                const ProbeDepth depth = probe_depth(g, p);
                if (depth.penetration <= 0.0) return;  // in the box, outside a rounded end
                const double facing = depth.normal.y();  // of the surface there, toward the tissue
                if (facing <= 0.0) return;  // an end's: pushing along the axis it does not
                // across the array, the pressure fades over the last edge_radius of the thickness
                const double fade = g.edge_radius > 0 ? std::min(1.0, (ht - std::abs(p.z())) / g.edge_radius) : 1.0;
                Contact ct;
                ct.nodes = tri;
                ct.weights = {wa, wb, wc};
                ct.penetration = depth.penetration;
                ct.stiffness = area * fade * std::max(0.0, law.slope(ct.penetration) * facing * facing -
                                                               law.pressure(ct.penetration) * (1.0 - facing * facing) * depth.turn);
                double closing = set.axis.dot(probe.velocity);  // the probe's speed into the skin, along the axis
                for (int k = 0; k < 3; ++k) closing -= ct.weights[k] * set.axis.dot(v.segment<3>(3 * Eigen::Index(tri[std::size_t(k)])));
                ct.force = std::max(0.0, law.pressure(ct.penetration) * area * facing * fade + law.damping_time * ct.stiffness * closing);
                if (fade < 1.0) ct.across_stiffness = law.pressure(ct.penetration) * area * facing / g.edge_radius;
                for (int k = 0; k < 3; ++k) force.segment<3>(3 * Eigen::Index(tri[std::size_t(k)])) += (ct.weights[k] * ct.force) * set.axis;
                set.total_force += ct.force;
                set.contacts.push_back(ct);
            });
        }
    return int(set.contacts.size());
}

void add_contact_stiffness_product(const ContactSet& set, const Eigen::VectorXd& p, Eigen::VectorXd& out)
{
    // the penalty pushes along the axis with stiffness k on the sample's displacement along it,
    // the weighted sum of the three nodes': K = k (w a)(w a)^T
    for (const Contact& c : set.contacts) {
        double along = 0;
        for (int k = 0; k < 3; ++k) along += c.weights[k] * set.axis.dot(p.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])));
        const double s = c.stiffness * along;
        for (int k = 0; k < 3; ++k) out.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])) += (s * c.weights[k]) * set.axis;
        if (c.across_stiffness == 0) continue;
        for (int k = 0; k < 3; ++k) {  // each node's own block (header)
            auto node_out = out.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)]));
            const double across = set.across.dot(p.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])));
            node_out += (c.across_stiffness * c.weights[k] * c.weights[k] * across) * set.across;
        }
    }
}

}  // namespace echosim::contact

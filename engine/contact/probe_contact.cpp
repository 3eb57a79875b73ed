#include "contact/probe_contact.hpp"

#include <algorithm>
#include <cmath>

namespace echosim::contact {
namespace {

constexpr double kCell = 2.0;  // broad-phase cell size on the face [mm]

int face_samples(const ProbeGeometry& g, int& nx, int& nz)
{
    nx = std::max(1, int(std::lround(g.face_width / g.sample_spacing)));
    nz = std::max(1, int(std::lround(g.face_thickness / g.sample_spacing)));
    return nx * nz;
}

}  // namespace

ContactSet make_contact_set(std::size_t node_count, std::size_t triangle_count, const ProbeGeometry& g)
{
    ContactSet s;
    int nx = 0, nz = 0;
    s.contacts.reserve(std::size_t(face_samples(g, nx, nz)));
    s.local.resize(node_count);
    s.cells_x = int(std::ceil(g.face_width / kCell));
    s.cells_z = int(std::ceil(g.face_thickness / kCell));
    s.cell_start.resize(std::size_t(s.cells_x * s.cells_z) + 1);
    // a triangle is filed in every cell its footprint overlaps; bound the total generously
    s.cell_items.resize(std::max<std::size_t>(1024, triangle_count * 4));
    s.candidates.reserve(triangle_count);
    return s;
}

int collide(const ProbeGeometry& g, const PenaltyLaw& law, const ProbeState& probe,
            const std::vector<std::array<std::uint32_t, 3>>& triangles, const Eigen::VectorXd& x, ContactSet& set,
            Eigen::VectorXd& force)
{
    set.contacts.clear();
    set.total_force = 0;
    if (!probe.active) return 0;
    const Eigen::Matrix3d to_local = probe.orientation.conjugate().toRotationMatrix();
    set.axis = probe.orientation * Eigen::Vector3d::UnitY();

    // nodes into the probe frame: x across the face, y along the beam, z across its thickness
    const std::size_t n = std::size_t(x.size() / 3);
    for (std::size_t i = 0; i < n; ++i) set.local[i] = to_local * (x.segment<3>(3 * Eigen::Index(i)) - probe.position);

    // broad phase: triangles that reach the box, filed by the face cells their footprint covers
    const double hw = g.face_width / 2, ht = g.face_thickness / 2;
    set.candidates.clear();
    std::fill(set.cell_start.begin(), set.cell_start.end(), 0u);
    auto cell_range = [&](const std::array<std::uint32_t, 3>& t, int& x0, int& x1, int& z0, int& z1) {
        double lx = 1e300, hx = -1e300, lz = 1e300, hz = -1e300, ly = 1e300;
        for (std::uint32_t k : t) {
            const auto& p = set.local[k];
            lx = std::min(lx, p.x()), hx = std::max(hx, p.x());
            lz = std::min(lz, p.z()), hz = std::max(hz, p.z());
            ly = std::min(ly, p.y());
        }
        // outside the face's footprint, or entirely in front of the face (y > 0): no contact
        if (hx < -hw || lx > hw || hz < -ht || lz > ht || ly > 0.0 || ly < -g.body_depth) return false;
        x0 = std::clamp(int((lx + hw) / kCell), 0, set.cells_x - 1);
        x1 = std::clamp(int((hx + hw) / kCell), 0, set.cells_x - 1);
        z0 = std::clamp(int((lz + ht) / kCell), 0, set.cells_z - 1);
        z1 = std::clamp(int((hz + ht) / kCell), 0, set.cells_z - 1);
        return true;
    };
    for (std::uint32_t t = 0; t < triangles.size(); ++t) {
        int x0 = 0, x1 = 0, z0 = 0, z1 = 0;
        if (!cell_range(triangles[t], x0, x1, z0, z1)) continue;
        set.candidates.push_back(t);
        for (int cz = z0; cz <= z1; ++cz)
            for (int cx = x0; cx <= x1; ++cx) ++set.cell_start[std::size_t(cz * set.cells_x + cx) + 1];
    }
    for (std::size_t c = 1; c < set.cell_start.size(); ++c) set.cell_start[c] += set.cell_start[c - 1];
    if (set.cell_start.back() > set.cell_items.size()) set.cell_items.resize(set.cell_start.back());  // rare: a crumpled mesh
    {
        // fill, using the cell starts as moving cursors, then shift them back
        for (std::uint32_t t : set.candidates) {
            int x0 = 0, x1 = 0, z0 = 0, z1 = 0;
            cell_range(triangles[t], x0, x1, z0, z1);
            for (int cz = z0; cz <= z1; ++cz)
                for (int cx = x0; cx <= x1; ++cx) set.cell_items[set.cell_start[std::size_t(cz * set.cells_x + cx)]++] = t;
        }
        for (std::size_t c = set.cell_start.size() - 1; c > 0; --c) set.cell_start[c] = set.cell_start[c - 1];
        set.cell_start[0] = 0;
    }

    // narrow phase: each face sample against the triangles of its cell
    int nx = 0, nz = 0;
    face_samples(g, nx, nz);
    const double area = (g.face_width / nx) * (g.face_thickness / nz);
    for (int iz = 0; iz < nz; ++iz)
        for (int ix = 0; ix < nx; ++ix) {
            const double sx = -hw + g.face_width * (ix + 0.5) / nx, sz = -ht + g.face_thickness * (iz + 0.5) / nz;
            const int cx = std::clamp(int((sx + hw) / kCell), 0, set.cells_x - 1);
            const int cz = std::clamp(int((sz + ht) / kCell), 0, set.cells_z - 1);
            const std::size_t cell = std::size_t(cz * set.cells_x + cx);
            // the deepest skin point under this sample (the face meets the outermost layer first)
            Contact best;
            for (std::uint32_t k = set.cell_start[cell]; k < set.cell_start[cell + 1]; ++k) {
                const auto& t = triangles[set.cell_items[k]];
                const Eigen::Vector3d &a = set.local[t[0]], &b = set.local[t[1]], &c = set.local[t[2]];
                // barycentric coordinates of (sx, sz) in the triangle's footprint
                const double d = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
                if (std::abs(d) < 1e-12) continue;
                const double wb = ((sx - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (sz - a.z())) / d;
                const double wc = ((b.x() - a.x()) * (sz - a.z()) - (sx - a.x()) * (b.z() - a.z())) / d;
                const double wa = 1.0 - wb - wc;
                constexpr double eps = -1e-9;
                if (wa < eps || wb < eps || wc < eps) continue;
                const double y = wa * a.y() + wb * b.y() + wc * c.y();
                const double penetration = -y;  // the skin is behind the face plane by this much
                if (penetration <= 0 || penetration > g.body_depth || penetration <= best.penetration) continue;
                best.nodes = t;
                best.weights = {wa, wb, wc};
                best.penetration = penetration;
            }
            if (best.penetration <= 0) continue;
            best.force = law.pressure(best.penetration) * area;
            best.stiffness = law.slope(best.penetration) * area;
            for (int k = 0; k < 3; ++k) force.segment<3>(3 * Eigen::Index(best.nodes[std::size_t(k)])) += best.weights[k] * best.force * set.axis;
            set.total_force += best.force;
            set.contacts.push_back(best);
        }
    return int(set.contacts.size());
}

void add_contact_product(const ContactSet& set, double h2, const Eigen::VectorXd& p, Eigen::VectorXd& out)
{
    // the penalty pushes along the axis with stiffness k on the sample's penetration, which moves
    // with the weighted sum of the three nodes along the axis: K = k (w a)(w a)^T
    for (const Contact& c : set.contacts) {
        double along = 0;
        for (int k = 0; k < 3; ++k) along += c.weights[k] * set.axis.dot(p.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])));
        const double s = h2 * c.stiffness * along;
        for (int k = 0; k < 3; ++k) out.segment<3>(3 * Eigen::Index(c.nodes[std::size_t(k)])) += (s * c.weights[k]) * set.axis;
    }
}

}  // namespace echosim::contact

#include "fit/interaction.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

namespace echosim::fit {

using tissue::SampleGrid;

SampleMesh sample_mesh(const MeasurementSet& set)
{
    SampleMesh mesh;
    std::array<bool, SampleGrid::count> seen{};
    for (const Sample& s : set.samples) {
        if (s.point >= SampleGrid::count)
            throw MeasurementError("measurements: point " + std::to_string(s.point) + " outside the 8 x 8 sample grid (0..63)");
        mesh.position[std::size_t(s.point)] = s.position;
        mesh.normal[std::size_t(s.point)] = s.normal;
        seen[std::size_t(s.point)] = true;
    }
    for (int p = 0; p < SampleGrid::count; ++p)
        if (!seen[std::size_t(p)]) throw MeasurementError("measurements: no sample at point " + std::to_string(p) + " of the 8 x 8 grid");
    auto add = [&](int r0, int c0, int r1, int c1) {
        if (r1 < 0 || c1 < 0 || r1 >= SampleGrid::rows || c1 >= SampleGrid::cols) return;
        const int i = SampleGrid::index(r0, c0), j = SampleGrid::index(r1, c1);
        mesh.springs.push_back({std::uint32_t(i), std::uint32_t(j), glm::length(mesh.position[std::size_t(i)] - mesh.position[std::size_t(j)])});
    };
    // the same topology as tissue::build_tissue_model at refine 1
    for (int r = 0; r < SampleGrid::rows; ++r)
        for (int c = 0; c < SampleGrid::cols; ++c) {
            add(r, c, r, c + 1);
            add(r, c, r + 1, c);
            add(r, c, r + 1, c + 1);
            add(r, c, r + 1, c - 1);
        }
    return mesh;
}

namespace {

// The grid's direction at node (r, c) along rows (dr = 1) or columns (dc = 1), one cell long
// (central difference inside, one-sided at the rim), projected off the probe axis.
glm::dvec3 tangent(const SampleMesh& mesh, int r, int c, int dr, int dc, const glm::dvec3& axis)
{
    const int r0 = std::max(r - dr, 0), r1 = std::min(r + dr, SampleGrid::rows - 1);
    const int c0 = std::max(c - dc, 0), c1 = std::min(c + dc, SampleGrid::cols - 1);
    const double cells = double((r1 - r0) + (c1 - c0));
    glm::dvec3 t = (mesh.position[std::size_t(SampleGrid::index(r1, c1))] - mesh.position[std::size_t(SampleGrid::index(r0, c0))]) / cells;
    return t - glm::dot(t, axis) * axis;
}

double overlap(double lo0, double hi0, double lo1, double hi1) { return std::max(0.0, std::min(hi0, hi1) - std::max(lo0, lo1)); }

}  // namespace

std::vector<InteractionSample> prepare_interaction(const SampleMesh& mesh, const MeasurementSet& set, const ProbeSpec& probe)
{
    std::vector<InteractionSample> out;
    out.reserve(set.samples.size());
    for (std::size_t k = 0; k < set.samples.size(); ++k) {
        const Sample& s = set.samples[k];
        const int p = s.point;
        const glm::dvec3 origin = mesh.position[std::size_t(p)];
        const glm::dvec3 axis = -mesh.normal[std::size_t(p)];  // the probe pushes inwards

        // which nodes are under the face, how much of each node's cell it covers, and how far
        // below its plane each lies at rest
        struct Under {
            int node;
            double gap, weight;
        };
        std::vector<Under> under;
        if (s.probe == ProbeKind::indenter) {
            under.push_back({p, 0.0, 1.0});
        } else {
            // transverse: the array runs around the thigh (along the grid's columns)
            const int r = SampleGrid::row_of(p), c = SampleGrid::col_of(p);
            const glm::dvec3 lateral = glm::normalize(tangent(mesh, r, c, 0, 1, axis));
            const glm::dvec3 elevation = glm::cross(lateral, axis);
            for (int i = 0; i < SampleGrid::count; ++i) {
                const glm::dvec3 d = mesh.position[std::size_t(i)] - origin;
                // node i's cell: half-way to its neighbours on each side
                const int ri = SampleGrid::row_of(i), ci = SampleGrid::col_of(i);
                const double cell_lat = glm::length(tangent(mesh, ri, ci, 0, 1, axis));
                const double cell_elev = glm::length(tangent(mesh, ri, ci, 1, 0, axis));
                const double x = glm::dot(d, lateral), z = glm::dot(d, elevation);
                // a rim node also stands for the skin beyond the grid, where the face may reach
                constexpr double beyond = 1e9;
                double x_lo = x - cell_lat / 2, x_hi = x + cell_lat / 2, z_lo = z - cell_elev / 2, z_hi = z + cell_elev / 2;
                if (ci == 0) x_lo = -beyond;
                if (ci == SampleGrid::cols - 1) x_hi = beyond;
                const bool rows_go_up = glm::dot(tangent(mesh, ri, ci, 1, 0, axis), elevation) > 0;
                if (ri == 0) (rows_go_up ? z_lo : z_hi) = rows_go_up ? -beyond : beyond;
                if (ri == SampleGrid::rows - 1) (rows_go_up ? z_hi : z_lo) = rows_go_up ? beyond : -beyond;
                const double cover = overlap(x_lo, x_hi, -probe.face_width_mm / 2, probe.face_width_mm / 2) / cell_lat *
                                     overlap(z_lo, z_hi, -probe.face_thickness_mm / 2, probe.face_thickness_mm / 2) / cell_elev;
                if (cover > 1e-9) under.push_back({i, std::max(0.0, glm::dot(d, axis)), cover});
            }
        }

        InteractionSample is;
        is.sample = k;
        is.force = s.force_N;
        std::vector<double> moved(SampleGrid::count, 0.0);
        std::vector<char> in_contact(SampleGrid::count, 0);
        for (const Under& u : under) {
            moved[std::size_t(u.node)] = std::max(0.0, s.depth_mm - u.gap);
            in_contact[std::size_t(u.node)] = 1;
            const double cosine = glm::dot(mesh.normal[std::size_t(p)], mesh.normal[std::size_t(u.node)]);
            is.contacts.push_back({u.node, moved[std::size_t(u.node)] * cosine, cosine, u.weight});
        }
        // the springs' pull on the pushed nodes, projected on the probe axis
        auto pulled = [&](int i, int j, double rest) {
            const glm::dvec3 pi = mesh.position[std::size_t(i)] + moved[std::size_t(i)] * axis;
            const glm::dvec3 pj = mesh.position[std::size_t(j)] + moved[std::size_t(j)] * axis;
            const double len = glm::length(pj - pi);
            return -(len - rest) * glm::dot((pj - pi) / len, axis);
        };
        for (const tissue::Spring& sp : mesh.springs) {
            if (in_contact[sp.i]) is.stretch += pulled(int(sp.i), int(sp.j), sp.rest_length);
            if (in_contact[sp.j]) is.stretch += pulled(int(sp.j), int(sp.i), sp.rest_length);
        }
        out.push_back(std::move(is));
    }
    return out;
}

}  // namespace echosim::fit

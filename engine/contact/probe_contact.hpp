// Probe-versus-skin contact (paper §5.1). The probe is an oriented box whose front face (40 x 10 mm,
// the transducer) touches the skin. The face is sampled by a grid of contact points; each casts
// along the probe axis onto the deformable patch's triangles (found through a uniform grid over the
// face, rebuilt every step, so a concave, deforming skin is fine). Where the skin lies in front of
// the face, i.e. inside the box, the penetration is measured from the face, a non-linear penalty
// pressure (after Deguet, Joukhadar and Laugier 1998) acts on the sample's share of the face, and
// the force goes to the triangle's three nodes by barycentric weights. Frictionless: the force is
// along the probe axis only, so the probe slides freely over the gel.
//
// Memory: every buffer is sized when the ContactSet is made; a step does not allocate.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace echosim::contact {

struct ProbeGeometry {
    double face_width = 40.0;      // along the array (probe x) [mm]
    double face_thickness = 10.0;  // elevational (probe z) [mm]
    double body_depth = 60.0;      // how far the box extends behind the face (probe -y) [mm]
    double sample_spacing = 1.0;   // between contact points on the face [mm]
};

// Penalty pressure [N/mm^2] at penetration p [mm]: k (p + p^2 / p0). Stiff against tissue (whose
// stress at 10 mm is about 0.01 N/mm^2), so the face sinks into the skin by well under a millimetre.
struct PenaltyLaw {
    double stiffness = 0.5;  // k [N/mm^3]
    double p0 = 1.0;         // [mm]
    double pressure(double p) const { return stiffness * (p + p * p / p0); }
    double slope(double p) const { return stiffness * (1.0 + 2.0 * p / p0); }
};

struct ProbeState {
    bool active = false;  // no probe, no contact
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // face centre, world [mm]
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // probe frame to world
};

struct Contact {
    std::array<std::uint32_t, 3> nodes{};
    Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric
    double penetration = 0;  // [mm]
    double force = 0;        // magnitude along the axis, on the tissue [N]
    double stiffness = 0;    // d force / d penetration [N/mm]
};

struct ContactSet {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // probe +y in world: into the tissue
    std::vector<Contact> contacts;
    double total_force = 0;  // sum of contact forces [N]: what pushes back on the probe

    // scratch of the broad phase, sized once
    std::vector<Eigen::Vector3d> local;  // node positions in the probe frame
    std::vector<std::uint32_t> cell_start, cell_items;
    std::vector<std::uint32_t> candidates;
    int cells_x = 0, cells_z = 0;
};

ContactSet make_contact_set(std::size_t node_count, std::size_t triangle_count, const ProbeGeometry& geometry);

// Finds the contacts of the probe with the triangles of the mesh at positions `x` (3n) and adds
// their forces into `force` (3n). Returns the number of contacts.
int collide(const ProbeGeometry& geometry, const PenaltyLaw& law, const ProbeState& probe,
            const std::vector<std::array<std::uint32_t, 3>>& triangles, const Eigen::VectorXd& x, ContactSet& set,
            Eigen::VectorXd& force);

// Adds the contact stiffness' product h^2 * K_c * p into `out` (the implicit solver's matrix).
void add_contact_product(const ContactSet& set, double h2, const Eigen::VectorXd& p, Eigen::VectorXd& out);

}  // namespace echosim::contact

// Probe-versus-skin contact (paper §5.1). The probe is a box whose front face (40 x 10 mm, the
// transducer) touches the skin, the ends of its array rounded; the skin is the deformable patch, a
// grid of triangles that may become concave. Each triangle carries material sample points
// (barycentric, fixed on the skin, a millimetre or less apart at rest); a sample inside the probe
// is in contact, its penetration its depth below the probe's surface in the plane of the array (a
// signed distance to the rounded profile, so it stays under the edge's radius where skin wraps an
// end). A non-linear penalty pressure (after Deguet, Joukhadar and Laugier 1998) acts on the
// sample's share of the skin's rest area; the part of it along the probe axis (all of it under the
// face, less over a rounded end, none beyond it), faded over the face's long edges, goes to the
// triangle's three nodes by the sample's barycentric weights. Along the axis only: frictionless, so
// the probe slides freely over the gel, and the skin is not pushed sideways either. The samples are
// material points, so the skin settles under a still probe (sampling the face instead would not).
//
// Why this shape (bench/RESULTS.md "Settling"): with both edges sharp and the pressure faded over
// 1 mm, skin wrapped around the array's ends under a deep press met the fade 10 mm below the face's
// plane and, pushed back along the axis, chattered in and out of contact from step to step (the
// force +-16 % at 16 mm). Rounding the long edges as well let the skin ahead of a probe sliding
// along the thigh (a long edge leading) pass into the probe's side unpushed; pushing along the
// surface's normal instead of the axis slid the frictionless skin off the rim and out from under
// the face. The long edges keep the fade: they plow the skin under the face when the probe slides.
//
// Broad phase: a BVH over the grid's cells (patch_bvh.hpp), refitted every step.
// Memory: every buffer is sized when the ContactSet is made; a step does not allocate.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "contact/patch_bvh.hpp"
#include "core/pose.hpp"
#include "core/probe_spec.hpp"

namespace echosim::contact {

struct ProbeGeometry {
    double face_width = kLinearProbe.face_width_mm;          // along the array (probe x) [mm]
    double face_thickness = kLinearProbe.face_thickness_mm;  // elevational (probe z) [mm]
    double body_depth = 60.0;      // how far the box extends behind the face (probe -y) [mm]
    // a real transducer's face is rounded at its rim: the array's ends are rounded with this radius,
    // and across the array the pressure fades to zero over this distance from the long edges, so
    // skin sliding past an edge feels no jump [mm]
    double edge_radius = 1.0;
};

// Penalty pressure [N/mm^2] at penetration p [mm], non-linear as Deguet et al.'s: quadratic up to
// p0 (k p^2 / (2 p0)), linear with slope k beyond. Its stiffness grows from zero as a contact
// starts, so a sample that comes into contact during a step does not meet a stiffness the implicit
// solver could not know about. Stiff against tissue (whose stress at 10 mm is about 0.01 N/mm^2):
// the face sinks into the skin by a few tenths of a millimetre.
struct PenaltyLaw {
    double stiffness = 0.5;  // k [N/mm^3]
    double p0 = 0.5;         // [mm]
    // damping of the contact [s]: the force also resists the rate of penetration with this times
    // the penalty stiffness, which takes the energy out of the skin's impacts on the face
    double damping_time = 2e-3;
    double pressure(double p) const { return p < p0 ? stiffness * p * p / (2.0 * p0) : stiffness * (p - 0.5 * p0); }
    double slope(double p) const { return p < p0 ? stiffness * p / p0 : stiffness; }
};

// The skin as the contact sees it: the patch grid's triangles (two per cell, cell k giving
// triangles 2k and 2k + 1) and how finely each is sampled.
struct PatchSurface {
    int rows = 0, cols = 0;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint8_t> subdivision;  // k: the triangle carries k^2 samples
    std::vector<double> sample_area;        // rest area of the triangle / k^2 [mm^2]
};

// `rest` holds 3 coordinates per node; samples end up at most `spacing` [mm] apart.
PatchSurface make_patch_surface(int rows, int cols, const Eigen::VectorXd& rest, double spacing = 1.0);

struct ProbeState {
    bool active = false;  // no probe, no contact
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // face centre, world [mm]
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // probe frame to world
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // of the face, world [mm/s]
};

// The probe in contact with its face at `face` (a pose in world: core/pose.hpp; pressed_along_beam
// presses one in), moving at `velocity` [mm/s].
inline ProbeState probe_at(const Pose& face, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero())
{
    ProbeState p;
    p.active = true;
    p.position = Eigen::Vector3d(face.position.x, face.position.y, face.position.z);
    p.orientation = Eigen::Quaterniond(face.orientation.w, face.orientation.x, face.orientation.y, face.orientation.z);
    p.velocity = velocity;
    return p;
}

struct Contact {
    std::array<std::uint32_t, 3> nodes{};
    Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric
    double penetration = 0;  // below the probe's surface [mm]
    double force = 0;        // magnitude along the axis, on the tissue [N]
    double stiffness = 0;    // d force / d (the sample's displacement against the axis) [N/mm]
    // how fast the force changes as the sample moves across the face's long sides (probe z),
    // outward [N/mm]: the fade's slope times the pressure, non-zero in the fade alone
    // (add_contact_stiffness_product)
    double across_stiffness = 0;
};

// Where a point given in the probe's frame lies against the probe's profile in the plane of the
// array (x, y; the box behind the face, its ends rounded): its penetration below the surface [mm]
// (negative outside) and the surface's outward normal there (probe frame; no z).
struct ProbeDepth {
    double penetration = 0;
    Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
    double turn = 0;  // how fast the normal turns as the point moves across it [1/mm]: 0 but over an end
};
ProbeDepth probe_depth(const ProbeGeometry& geometry, const Eigen::Vector3d& local);

struct ContactSet {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // probe +y in world: into the tissue
    Eigen::Vector3d across = Eigen::Vector3d::UnitZ();  // probe +z in world: across the long sides
    std::vector<Contact> contacts;
    double total_force = 0;  // sum of contact forces [N]: what pushes back on the probe
    GridBvh bvh{2, 2};
    std::vector<std::uint32_t> cells;  // broad-phase result
};

ContactSet make_contact_set(const PatchSurface& surface);

// Finds the contacts of the probe with the skin at positions `x` (3n, velocities `v`) and adds
// their forces into `force` (3n). Returns the number of contacts.
int collide(const ProbeGeometry& geometry, const PenaltyLaw& law, const ProbeState& probe, const PatchSurface& surface,
            const Eigen::VectorXd& x, const Eigen::VectorXd& v, ContactSet& set, Eigen::VectorXd& force);

// Adds K_c p into `out` (3n each): the contacts' stiffness, the negated Jacobian of their forces
// with respect to the node positions, for the implicit step's right-hand side. (The solver's
// matrix carries the same blocks, with damping and the time step folded in: physics/grid_system.)
// Per sample k (w a)(w a)^T, k the derivative of its force along the axis with respect to the
// sample's displacement along it: over a rounded end the penetration grows by the facing f and the
// facing itself falls, k = area fade (slope f^2 - pressure (1 - f^2) turn), kept >= 0 so the
// solver's matrix stays positive definite. The force's change as the skin moves across the axis
// (over an end or a long edge's fade) is left to the next step; the matrix stays symmetric.
// Across the long sides, where that change is steepest (the fade: the whole pressure per
// edge_radius), each node of the sample also gets k_a w^2 c c^T, c the across direction and k_a
// the sample's across_stiffness: a stiffness with no force of its own, which holds the skin in the
// fade from moving across it faster than the step can follow. Without it, skin wrapped up the
// long sides under a deep press chattered in and out of the fade, the force on the probe moving 2
// to 3 N from one 1 ms step to the next (a large patient's 30 mm press; bench/RESULTS.md, "The
// contact's long sides"): the fade pushes along the axis by where the skin lies across it, a
// force that is not a potential's, and explicit over one step it fed the motion. A still probe's
// force settles to what it did (the term is zero at rest), but the skin in the fade moves across
// it only as fast as the step can follow: under a deep still press the tissue comes to rest in
// 0.5 to 0.7 s (was 0.2), and the headless exam runs some 7 % slower. The solver's matrix
// carries the same diagonal blocks (physics/grid_system).
void add_contact_stiffness_product(const ContactSet& set, const Eigen::VectorXd& p, Eigen::VectorXd& out);

}  // namespace echosim::contact

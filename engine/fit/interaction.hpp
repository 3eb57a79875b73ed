// The paper's simplified interaction model between a probe and the tissue model (§3.2.1), which
// the fit works with: the probe pushes the nodes under its face straight along its axis, the other
// nodes stay where they are (deformation of the thigh is local). The force on the probe is then
//     F(depth) = lambda * S(depth) + sum over contact nodes i of cos_i * f_i(c_i)
//     F(depth) = lambda * S(depth) + sum over contact nodes i of w_i * cos_i * f_i(c_i)
// where S is the stretch of the surface springs projected on the probe axis (geometry only),
// f_i the non-linear spring of node i compressed by c_i, cos_i the angle between its normal and
// the probe axis, and w_i the share of node i's patch of skin that the face covers (each node's
// spring stands for the tissue column under its cell of the grid). The indenter acts on one node
// with its whole spring (w = 1), as in the paper; the pseudo-probe's 40 x 10 mm face, held
// transversely, covers parts of three to five nodes' cells on the 64-node mesh (about three cells'
// worth), each node pushed from the depth at which the curved skin under it meets the flat face.
//
// The geometry is computed once per sample (`prepare_interaction`), so each evaluation of the
// model during the fit costs a handful of flops.
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "core/probe_spec.hpp"
#include "fit/measurements.hpp"
#include "tissue/nonlinear_spring.hpp"
#include "tissue/sample_grid.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::fit {

// The 64-node mesh of the sample points, as the measurements place them.
struct SampleMesh {
    std::array<glm::dvec3, tissue::SampleGrid::count> position{};
    std::array<glm::dvec3, tissue::SampleGrid::count> normal{};  // outward
    std::vector<tissue::Spring> springs;
};

// Throws MeasurementError when the set does not hold the 64 points of the 8 x 8 grid.
SampleMesh sample_mesh(const MeasurementSet& set);

struct ContactTerm {
    int node = 0;
    double compression = 0;  // c_i [mm]
    double cosine = 1;       // cos_i
    double weight = 1;       // w_i
};

struct InteractionSample {
    std::size_t sample = 0;  // index into the measurement set
    double force = 0;        // measured [N]
    double stretch = 0;      // S [mm]
    std::vector<ContactTerm> contacts;
};

// `probe`: the pseudo-probe's face, its array across the thigh, its thickness along it.
std::vector<InteractionSample> prepare_interaction(const SampleMesh& mesh, const MeasurementSet& set,
                                                   const ProbeSpec& probe = kLinearProbe);

// The model force for one prepared sample, with per-node (a, b) and lambda; false when a node's
// spring would be compressed past its bottoming depth (the parameters are infeasible there).
template <class T, class AB>
bool interaction_force(const InteractionSample& s, const AB& ab, const T& lambda, T& force)
{
    force = lambda * s.stretch;
    for (const ContactTerm& c : s.contacts) {
        if (c.compression <= 0) continue;
        const T& a = ab(c.node, 0);
        const T& b = ab(c.node, 1);
        if (!tissue::spring_holds(T(c.compression), a, b)) return false;
        force += c.weight * c.cosine * tissue::spring_force(T(c.compression), a, b);
    }
    return true;
}

}  // namespace echosim::fit

// The two-layer tissue model of the thigh (paper §3.2, Fig. 3), immutable once built: a surface
// mesh of nodes joined by linear spring-dampers f = lambda x - mu xdot (lambda, mu uniform), and at
// every node a non-linear spring normal to the skin, anchored at the bone (nonlinear_spring.hpp),
// whose a, b vary over the patch. Mutable simulation state lives elsewhere (TissueState, with the
// dynamics), as MuJoCo keeps mjModel apart from mjData.
//
// Resolution: the fit works on the 64 sample points (refine = 1: one node per point, an 8 x 8
// grid). Any refinement r gives a (7r + 1)^2 grid over the same area whose every r-th node is a
// sample point; a and b of the other nodes are interpolated bilinearly from the samples in the
// physically meaningful quantities (rest stiffness 1/b and bottoming depth b/a). Each node then
// carries 1/r^2 of a sample point's area, so its spring force is scaled by 1/r^2 (a and b by r^2,
// which keeps b/a) and its mass likewise: the patch as a whole answers the same at any resolution.
// The surface damping mu, set for a damping ratio of a node's mass, scales by 1/r^2 too; lambda
// stays (a 2-D spring network's membrane stiffness does not depend on its spacing).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/skin_surface.hpp"
#include "tissue/sample_grid.hpp"

namespace echosim::tissue {

struct Spring {
    std::uint32_t i = 0, j = 0;
    double rest_length = 0;  // [mm]
};

// What the fit found at the 64 sample points (and what a model is rebuilt from at any resolution).
struct SampleParameters {
    std::array<double, SampleGrid::count> a{};  // [1/N]
    std::array<double, SampleGrid::count> b{};  // [mm/N]
    double lambda = 0;  // surface spring stiffness [N/mm]
    double mu = 0;      // surface spring damping [N s/mm]
};

struct FitStatistics {
    double mae_N = 0, sd_N = 0, rel_error = 0;  // over all samples
    double mae_indenter_N = 0, mae_probe_N = 0;
    int samples = 0;
    std::string method;
    double seconds = 0;
};

struct TissueModel {
    int rows = 0, cols = 0, refine = 1;
    std::vector<glm::dvec3> positions;  // rest positions on the skin [mm], row-major
    std::vector<glm::dvec3> normals;    // outward unit normals
    std::vector<double> mass;           // [kg]
    std::vector<double> a, b;           // per-node non-linear spring (already scaled by 1/r^2)
    std::vector<std::uint8_t> boundary; // 1 on the grid's rim (fixed to the leg in the dynamics)
    std::vector<Spring> springs;        // structural and shear (diagonal) springs
    double lambda = 0, mu = 0;
    SampleParameters samples;
    FitStatistics fit;
    std::string provenance;  // where the parameters came from (data file, method, date)

    std::size_t node_count() const { return positions.size(); }
    std::uint32_t node(int row, int col) const { return std::uint32_t(row * cols + col); }
    // the node at sample point p (every refine-th node)
    std::uint32_t sample_node(int point) const
    {
        return node(SampleGrid::row_of(point) * refine, SampleGrid::col_of(point) * refine);
    }
};

// Mass of skin and subcutaneous tissue each unit of patch area carries in the dynamics [kg/mm^2]:
// 1.05 g/cm^3 over a 10 mm layer. Not identifiable from quasi-static data; a stated assumption.
inline constexpr double kSurfaceMassPerArea = 1.05e-6 * 10.0;

// The model on the sample area of `skin`'s exam patch at refinement `refine` (1..64).
TissueModel build_tissue_model(const SkinSurface& skin, const SampleParameters& params, int refine);

}  // namespace echosim::tissue

// The CPU twin of the deform kernel (compute/deform.comp): the same column walk
// (compute/deform_column.h, compiled here as C++), over a label map in host memory. The reference
// the GPU kernel is tested against, and the `--cpu` path.
#pragma once

#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "deform_bindings.h"
#include "echo/echo_frame.hpp"
#include "echo/tissue_mechanics.hpp"
#include "io/nrrd.hpp"

namespace echosim::echo {

// The deform map, one vec2(source y [mm], gain [dB]) per pixel, row-major. `labels`: uint8 codes
// on the grid `params.probe_to_index` maps to, or null (the paper's linear deformation: set
// DEFORM_PAPER_LINEAR). `profile`: one per column. Throws std::invalid_argument on a profile of
// the wrong size or labels that are not uint8.
std::vector<glm::vec2> deform_cpu(const io::Volume* labels, std::span<const ColumnProfile> profile, const TissueTable& tissues,
                                  const kernels::DeformParams& params);

}  // namespace echosim::echo

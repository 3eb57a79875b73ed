// The echographic image pipeline on the CPU: deform ▶ slice ▶ post, each stage the twin of its
// compute kernel (compute/). What `echosim slice --cpu` runs, and the reference the GPU pipeline
// (engine/image/echo_image_gpu.hpp) is tested against.
#pragma once

#include "echo/echo_frame.hpp"
#include "io/nrrd.hpp"

namespace echosim::echo {

// `volume`: uint8 grey levels; `labels`: uint8 tissue codes on the same grid, or null (the paper's
// linear deformation). With `want_labels` (and labels), EchoImage::labels is filled. Throws
// std::invalid_argument naming what does not fit (plane, profile size, voxel types, grids).
EchoImage render_echo_cpu(const io::Volume& volume, const io::Volume* labels, const ImagePlane& plane, const EchoFrame& frame,
                          const ScannerSettings& scanner, const PatientCase& patient, bool want_labels = false);

// Throws std::invalid_argument unless `volume` is uint8 and `labels` (when given) is uint8 on the
// same grid (size, directions and origin).
void check_volumes(const io::Volume& volume, const io::Volume* labels);

}  // namespace echosim::echo

// The echographic image pipeline on the CPU: deform ▶ slice ▶ post, each stage the twin of its
// compute kernel (compute/). What `echosim slice --cpu` runs, and the reference the GPU pipeline
// (engine/image/echo_image_gpu.hpp) is tested against.
#pragma once

#include "echo/echo_frame.hpp"
#include "io/nrrd.hpp"

namespace echosim::echo {

// `volume`: uint8 grey levels; `labels`: uint8 tissue codes on the same grid, or null (the paper's
// linear deformation). With `want_labels` (and labels), EchoImage::labels is filled. Generative
// `imaging` synthesises the image from the labels where the deform map puts each pixel's tissue
// (echo::synthesize_live) in place of the slice, and needs them. Throws std::invalid_argument
// naming what does not fit (plane, profile size, voxel types, grids, generative without labels).
EchoImage render_echo_cpu(const io::Volume& volume, const io::Volume* labels, const ImagePlane& plane, const EchoFrame& frame,
                          const ScannerSettings& scanner, const PatientCase& patient, bool want_labels = false,
                          Imaging imaging = Imaging::interpolative);

// Throws std::invalid_argument unless `volume` is uint8 and `labels` (when given) is uint8 on the
// same grid (size, directions and origin).
void check_volumes(const io::Volume& volume, const io::Volume* labels);

}  // namespace echosim::echo

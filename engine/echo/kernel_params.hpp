// The three kernels' parameters for one frame (compute/*_bindings.h), made in one place from the
// frame's inputs, for the CPU twin and the GPU dispatcher alike.
#pragma once

#include <cstdint>

#include "deform_bindings.h"
#include "echo/echo_frame.hpp"
#include "io/nrrd.hpp"
#include "post_bindings.h"
#include "slice_bindings.h"

namespace echosim::echo {

// How far above the face the undeformed skin may lie and still be walked by the deform stage [mm]:
// the deepest press the simulator allows (25 mm) with room for a tilted probe.
inline constexpr double kMaxSkinAboveFaceMm = 35.0;

struct KernelParams {
    kernels::DeformParams deform;
    kernels::SliceParams slice;
    kernels::PostParams post;
};

// The finest the deform stage resolves the tissue [mm], down a column and across the image: the
// deformation is smooth but at the lumens' edges, and those the walk places within a quarter step
// (deform_column.h reads the labels at each step's quarters), 0.075 mm; the map is spread sideways
// over millimetres anyway. The walk's cost goes with columns x steps: at 0.2 mm a 0.1 mm volume's
// 1024² frame ran 60-85 fps on lavapipe, at 0.3 mm 106-130 (bench/RESULTS.md, 2026-11-26).
inline constexpr double kDeformResolutionMm = 0.3;
// The deform stage's step down a column [mm]: no finer than a pixel, nor than the label grid (the
// labels are read at the nearest voxel: a finer walk reads the same voxel twice), nor than
// kDeformResolutionMm.
double deform_step_mm(const io::Volume& grid, const ImagePlane& plane);
// The walk's steps per column the scratch holds.
std::uint32_t deform_max_steps(const io::Volume& grid, const ImagePlane& plane);
// The deform stage's columns across the image: as many as the image's, but no finer than the label
// grid nor kDeformResolutionMm, for the same reasons (a 1024-column image over 0.3 mm labels walks
// 134 columns). The slice stage reads the map between them, linearly (slice_bindings.h, map_tap).
std::uint32_t deform_columns(const io::Volume& grid, const ImagePlane& plane);
// Map columns per image column (SliceParams::map_step) for the deform map's `map_columns`
// (deform_columns): 1 when the map is as fine as the image.
float map_step(std::uint32_t map_columns, const ImagePlane& plane);
// The frame's skin profile at the deform stage's `columns` column centres, linear between the
// image columns' (empty when the frame presses nothing).
std::vector<ColumnProfile> deform_profiles(const EchoFrame& frame, const ImagePlane& plane, std::uint32_t columns);

// `grid`: the volume's geometry (its voxels are not read); `labelled`: whether a label map
// shares its grid (else the paper's linear deformation); `warped`: whether the frame presses.
KernelParams make_kernel_params(const io::Volume& grid, const ImagePlane& plane, const EchoFrame& frame,
                                const ScannerSettings& scanner, const PatientCase& patient, bool labelled);

}  // namespace echosim::echo

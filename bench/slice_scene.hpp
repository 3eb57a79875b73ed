// The inputs of the "slice" suite: the thigh phantom's volumes at 0.3 mm and 0.1 mm voxels, and
// pressed frames of the default probe pose, one per image size.
//
// The volumes: 40 x 60 x 120 mm (lateral x beam x elevation), the size of the VTK reference the
// issue compares with (vtkImageReslice on a 400 x 600 x 1200 8-bit volume at 0.1 mm); their axes
// are the resting probe's, turned a few degrees, so the image is an oblique plane through their
// middle. Grey levels: random speckle (the content does not change the cost). Labels: the
// phantom's tissue codes, so the deform stage walks real tissue; the 0.1 mm labels are the 0.3 mm
// ones upsampled by nearest neighbour (the phantom for 288 M voxels would take minutes).
#pragma once

#include <cstdint>

#include "echo/echo_frame.hpp"
#include "io/nrrd.hpp"

namespace echosim::bench {

struct SliceVolume {
    double voxel_mm = 0;
    io::Volume grey;    // uint8 speckle
    io::Volume labels;  // uint8 tissue codes, same grid
};

// The 0.3 mm volume (134 x 200 x 400 voxels), its labels from the phantom (all cores).
SliceVolume make_coarse_volume();
// The 0.1 mm volume (400 x 600 x 1200 voxels) over the same box, labels from `coarse`.
SliceVolume make_fine_volume(const SliceVolume& coarse);

// The probe at its default pose pressed 12 mm in and settled (a lock-step session with the plane):
// what a live frame of that plane gets.
echo::EchoFrame pressed_frame(const echo::ImagePlane& plane);

}  // namespace echosim::bench

// Where an image plane meets a volume, and a probe pose that puts it there: `slice` of a user's own
// volume, whose space need not be our leg's, so the simulator's default pose (the exam patch's
// centre) may miss it entirely and give a black image that looks like an answer.
#pragma once

#include "core/pose.hpp"
#include "echo/echo_frame.hpp"
#include "io/nrrd.hpp"

namespace echosim::echo {

// The share (0..1) of the image's pixels whose centres lie in the volume (within half a voxel of
// its outermost voxel centres), judged on at most 64 x 64 of them spread over the image.
double plane_coverage(const io::Volume& volume, const ImagePlane& plane, const Pose& face);

// The probe laid on the volume as a tracked frame lies in a PLUS sweep (MF): the array along the
// volume's first axis, the beam along its second, the face on the second axis's first voxels, in
// the middle of the first and third axes.
Pose pose_on_volume(const io::Volume& volume);

}  // namespace echosim::echo

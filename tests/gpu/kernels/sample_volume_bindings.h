// Bindings of the test kernel sample_volume.comp (tests/gpu/compute_test.cpp): a volume sampled
// through a sampler at a grid of points, one float per point.
#ifndef ECHOSIM_TEST_SAMPLE_VOLUME_BINDINGS_H
#define ECHOSIM_TEST_SAMPLE_VOLUME_BINDINGS_H

#ifdef __cplusplus
#include <glm/vec4.hpp>
namespace echosim::test::kernels {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

#define SAMPLE_VOLUME_GROUP_SIZE 4      // invocations per workgroup along x, y and z (a 3-D dispatch)
#define SAMPLE_VOLUME_VOLUME_BINDING 0  // sampler3D: the volume, red channel
#define SAMPLE_VOLUME_GRID_BINDING 1    // uniform SampleGrid
#define SAMPLE_VOLUME_OUT_BINDING 2     // storage buffer: float per point, x fastest, then y, then z

// The points, in normalised texture coordinates: origin + (i, j, k) * step.
struct SampleGrid {
    vec4 origin;  // xyz, w unused
    vec4 step;    // xyz, w unused
    uvec4 count;  // points along x, y, z; w unused
};

#ifdef __cplusplus
}  // namespace echosim::test::kernels
#endif
#endif

// Bindings of the test kernel pattern.comp (tests/gpu/compute_test.cpp and the frame tests): a 2-D
// dispatch writing a known pattern into a storage image. The tests compute the pattern themselves.
#ifndef ECHOSIM_TEST_PATTERN_BINDINGS_H
#define ECHOSIM_TEST_PATTERN_BINDINGS_H

#ifdef __cplusplus
#include <cstdint>
namespace echosim::test::kernels {
using uint = std::uint32_t;
#endif

#define PATTERN_GROUP_X 8
#define PATTERN_GROUP_Y 8
#define PATTERN_IMAGE_BINDING 0   // storage image, rgba8 (UNORM)
#define PATTERN_PARAMS_BINDING 1  // uniform PatternParams

struct PatternParams {
    uint seed;    // makes each image of the test its own
    uint width;   // [px] of the image
    uint height;  // [px]
    uint unused;
};

#ifdef __cplusplus
}  // namespace echosim::test::kernels
#endif
#endif

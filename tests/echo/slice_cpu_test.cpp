// The CPU slice paths on a volume one voxel thick (a 2-D image, read as one slice): every tap stays
// inside the volume (under AddressSanitizer a read past it fails the test), and a plane lying in
// the slice reads its voxels back exactly, as the GPU's clamping sampler does.
#include <gtest/gtest.h>

#include "echo/slice_cpu.hpp"

namespace echosim::echo {
namespace {

// 6 x 4 x 1 voxels of 1 mm at the origin, voxel (i, j) = 10 i + 40 j + 5
io::Volume one_slice()
{
    io::Volume v;
    v.size = {6, 4, 1};
    v.data.resize(v.voxel_count());
    for (std::size_t j = 0; j < 4; ++j)
        for (std::size_t i = 0; i < 6; ++i) v.data[v.index(i, j, 0)] = std::uint8_t(10 * i + 40 * j + 5);
    return v;
}

TEST(SliceCpu, AVolumeOneVoxelThickReadsItsVoxelsOnThePlaneThroughIt)
{
    const io::Volume v = one_slice();
    // the probe frame on the volume's axes, 6 mm wide in 1 mm pixels, placed so that pixel column c
    // is centred on voxel c and row r on voxel r (pixel centres at x = c + 0.5 - 3, y = r + 0.5)
    Pose pose;
    pose.position = {2.5f, -0.5f, 0.0f};
    ScanSpec spec;
    spec.width_mm = 6.0;
    spec.depth_mm = 4.0;
    spec.pixel_mm = 1.0;
    const std::vector<std::uint8_t> grey = slice_grey(v, pose, spec);
    ASSERT_EQ(grey.size(), 24u);
    for (std::size_t j = 0; j < 4; ++j)
        for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(grey[j * 6 + i], v.data[v.index(i, j, 0)]) << i << "," << j;

    // the kernel's twin: the same plane through probe_to_index (probe mm -> index: x + 2.5, y - 0.5)
    kernels::SliceParams p{};
    glm::mat4 to_index(1.0f);
    to_index[3] = glm::vec4(2.5f, -0.5f, 0.0f, 1.0f);
    p.probe_to_index = to_index;
    p.columns = 6;
    p.rows = 4;
    p.pixel_x_mm = p.pixel_y_mm = 1.0f;
    p.width_mm = 6.0f;
    p.flags = SLICE_GREY;
    const SliceOutput out = slice_stage_cpu(v, nullptr, {}, p);
    ASSERT_EQ(out.grey.size(), 24u);
    for (std::size_t j = 0; j < 4; ++j)
        for (std::size_t i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(out.grey[j * 6 + i], float(v.data[v.index(i, j, 0)])) << i << "," << j;
}

}  // namespace
}  // namespace echosim::echo

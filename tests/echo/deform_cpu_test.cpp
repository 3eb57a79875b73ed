// The deform stage's model on the CPU twin (compute/deform_column.h run as C++): the stress under
// the face against Newmark's closed form, the paper's linear deformation against its analytic map,
// and a probe at rest or lifted off the skin leaving the image as the volume has it.
#include "echo/deform_cpu.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "deform_bindings.h"
#include "echo/echo_image_cpu.hpp"
#include "echo/kernel_params.hpp"
#include "echo/slice_cpu.hpp"
#include "echo/tissue_mechanics.hpp"
#include "echo/echo_test_volumes.hpp"
#include "session/session.hpp"

namespace echosim::echo {
namespace {

TEST(FaceInfluence, IsTheElasticHalfSpaceUnderARectangle)
{
    using kernels::corner_influence;
    using kernels::face_influence;
    // Boussinesq's point load, sigma_z = 3 P z^3 / (2 pi R^5), summed over the 40 x 10 mm face
    // (midpoint rule, 0.05 mm cells): the closed form's independent check
    const auto boussinesq = [](double x, double z) {
        double sum = 0;
        const double cell = 0.05;
        for (double u = -20 + cell / 2; u < 20; u += cell)
            for (double v = -5 + cell / 2; v < 5; v += cell) {
                const double r2 = (x - u) * (x - u) + v * v + z * z;
                sum += 3 * z * z * z / (2 * 3.141592653589793 * r2 * r2 * std::sqrt(r2)) * cell * cell;
            }
        return sum;
    };
    for (const double z : {2.0, 10.0, 30.0})
        for (const double x : {0.0, 15.0, 30.0}) EXPECT_NEAR(face_influence(float(x), float(z), 40, 10), boussinesq(x, z), 2e-3) << x << ", " << z;
    EXPECT_NEAR(face_influence(0, 0.01f, 40, 10), 1.0f, 1e-3f);  // just under the face, all of it
    // a corner of an infinite quadrant carries a quarter; the stress falls with depth and away from the face
    EXPECT_NEAR(corner_influence(1e4f, 1e4f, 1.0f), 0.25f, 1e-3f);
    float last = 1.0f;
    for (float z = 1; z < 60; z += 3) {
        const float i = face_influence(0, z, 40, 10);
        EXPECT_LT(i, last);
        EXPECT_GT(face_influence(0, z, 40, 10), face_influence(25, z, 40, 10));
        last = i;
    }
}

// a probe pose whose frame is the world's, and a volume grid of 0.5 mm voxels around it
struct Flat {
    io::Volume grid = io::make_volume({100, 140, 9}, io::VoxelType::uint8);
    ImagePlane plane{40, 50, 80, 100};
    Flat()
    {
        grid.directions = glm::dmat3(0.5);
        grid.origin = {-25, -15, -2};
    }
};

TEST(DeformCpu, WithoutLabelsIsThePapersLinearDeformation)
{
    Flat f;
    EchoFrame frame;
    const float skin = -6.0f, shift = 6.0f;  // the skin 6 mm above the face, pressed down onto it
    frame.columns.assign(f.plane.columns, {skin, shift});
    frame.skin_pressure_kpa = 20;
    const KernelParams k = make_kernel_params(f.grid, f.plane, frame, {}, {}, false);
    const auto map = deform_cpu(nullptr, frame.columns, paper_linear_mechanics(), k.deform);
    // uniform compression between the pressed skin (y = 0) and the image's depth (50 mm, held):
    // a pixel at y came from y0 = skin + (y - (skin + shift)) (depth - skin) / (depth - skin - shift)
    const double depth = 50;
    for (std::uint32_t r = 0; r < f.plane.rows; ++r)
        for (std::uint32_t c : {0u, 40u, 79u}) {
            const double y = (r + 0.5) * f.plane.pixel_y_mm();
            const double expected = skin + (y - (skin + shift)) * (depth - skin) / (depth - skin - shift);
            ASSERT_NEAR(map[r * f.plane.columns + c].x, expected, 0.02) << "row " << r;
            ASSERT_EQ(map[r * f.plane.columns + c].y, 0.0f);
        }
}

TEST(DeformCpu, AnUnpressedSkinLeavesTheImageUndeformed)
{
    // the skin touched but not moved, no pressure: every pixel maps back to itself
    Flat f;
    EchoFrame frame;
    frame.columns.assign(f.plane.columns, {-0.0f, 0.0f});
    const KernelParams k = make_kernel_params(f.grid, f.plane, frame, {}, {}, true);
    io::Volume labels = io::make_volume(f.grid.size, io::VoxelType::uint8);
    labels.directions = f.grid.directions;
    labels.origin = f.grid.origin;
    std::fill(labels.data.begin(), labels.data.end(), std::uint8_t(Tissue::fat));
    const auto map = deform_cpu(&labels, frame.columns, tissue_mechanics({}), k.deform);
    for (std::uint32_t r = 0; r < f.plane.rows; ++r)
        ASSERT_NEAR(map[r * f.plane.columns + 7].x, (r + 0.5) * f.plane.pixel_y_mm(), 1e-4) << "row " << r;
}

TEST(DeformCpu, AProbeLiftedOffTheSkinLeavesTheImageUndeformed)
{
    const scene::LegModel leg;
    session::Session s;
    const test::LabelledVolume v = test::phantom_volume(leg, Case::healthy, s.probe().rest);
    for (const double lift : {0.0, 3.0}) {
        // the probe held `lift` mm above the skin: the skin stays where it is, nothing presses
        s.place_probe({pressed_along_beam(s.probe().rest, -lift), 0.0});
        s.advance(0.05);
        const EchoFrame frame = *s.view().echo;
        EXPECT_EQ(s.view().probe_force_N, 0.0);
        EXPECT_TRUE(frame.columns.empty());  // nothing touches: no indentation
        EchoFrame still = frame;
        still.columns.clear();
        const EchoImage pressed = render_echo_cpu(v.grey, &v.labels, s.image_plane(), frame, {}, s.patient(), true);
        const EchoImage undeformed = render_echo_cpu(v.grey, &v.labels, s.image_plane(), still, {}, s.patient(), true);
        EXPECT_EQ(pressed.rgba, undeformed.rgba) << "lifted " << lift << " mm";
        EXPECT_EQ(pressed.labels, undeformed.labels);
    }
}

TEST(SliceCpu, TheUndeformedSliceIsATrilinearResamplingOfTheVolume)
{
    // the slice stage's twin (float, the sampler's arithmetic) against slice_grey (double, written
    // for the reconstruction's tests), on random voxels through an oblique plane
    io::Volume v = io::make_volume({90, 120, 60}, io::VoxelType::uint8);
    std::uint32_t x = 12345;
    for (std::uint8_t& b : v.data) b = std::uint8_t((x = x * 1664525u + 1013904223u) >> 24);
    v.directions = glm::dmat3(0.4);
    v.origin = {-18, -5, -12};
    const Pose pose = pose_from_axes({0, 0, 0}, glm::normalize(glm::vec3(1, 0.1f, 0.2f)), glm::normalize(glm::vec3(-0.1f, 1, 0.05f)));
    ScanSpec spec;
    spec.pixel_mm = 0.1;
    spec.width_mm = 30;
    spec.depth_mm = 35;
    const ImagePlane plane = plane_with_pixel(spec.width_mm, spec.depth_mm, spec.pixel_mm);
    EchoFrame frame;
    frame.face = pose;
    const KernelParams k = make_kernel_params(v, plane, frame, {}, {}, false);
    const SliceOutput twin = slice_stage_cpu(v, nullptr, {}, k.slice);
    const std::vector<std::uint8_t> reference = slice_grey(v, pose, spec);
    ASSERT_EQ(twin.grey.size(), reference.size());
    std::size_t inside = 0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        // slice_grey rounds to 8 bits; the plane's geometry in float moves a sample by < 1e-4 voxel
        ASSERT_NEAR(twin.grey[i], float(reference[i]), 0.51f + 0.05f) << "pixel " << i;
        inside += reference[i] != 0;
    }
    EXPECT_GT(inside, reference.size() / 2);  // the plane mostly inside the volume
}

}  // namespace
}  // namespace echosim::echo

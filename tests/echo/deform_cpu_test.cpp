// The deform stage's model on the CPU twin (compute/deform_column.h run as C++): the stress under
// the face against Newmark's closed form, the paper's linear deformation against its analytic map,
// a probe at rest or lifted off the skin leaving the image as the volume has it, and a closing
// vein's walls meeting as one bright line while the tissue around it sinks without a seam, and
// what lies under it losing its enhancement over the beam's width.
#include "echo/deform_cpu.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "deform_bindings.h"
#include "slice_bindings.h"
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
    // the skin 6 mm above the face, pressed down onto it, and on one side of the image 3 mm further
    // (each column on its own: no sideways spread)
    const float skin = -6.0f;
    const auto shift_at = [&](std::uint32_t c) { return c < f.plane.columns / 2 ? 6.0f : 9.0f; };
    for (std::uint32_t c = 0; c < f.plane.columns; ++c) frame.columns.push_back({skin, shift_at(c)});
    frame.skin_pressure_kpa = 20;
    const KernelParams k = make_kernel_params(f.grid, f.plane, frame, {}, {}, false);
    const auto map = deform_cpu(nullptr, frame.columns, paper_linear_mechanics(), k.deform);
    // uniform compression between the pressed skin (y = skin + shift) and the image's depth (50 mm,
    // held): a pixel at y came from y0 = skin + (y - (skin + shift)) (depth - skin) / (depth - skin -
    // shift); above the skin, the gel moved with it: y0 = y - shift
    const double depth = 50;
    for (std::uint32_t r = 0; r < f.plane.rows; ++r)
        for (std::uint32_t c : {0u, 38u, 39u, 40u, 41u, 79u}) {
            const double y = (r + 0.5) * f.plane.pixel_y_mm(), shift = shift_at(c);
            const double expected =
                y < skin + shift ? y - shift : skin + (y - (skin + shift)) * (depth - skin) / (depth - skin - shift);
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

TEST(DeformCpu, ABoneUnderTooLittleSoftTissueToTakeThePressStaysPut)
{
    // 16 mm of muscle over a 10 mm slab of bone, muscle again below it; the skin 12 mm above the
    // face pressed onto it: more than the muscle's largest strain (half its thickness, 8 mm) can
    // take. The bone is held (the tissue model's springs are anchored there), and shields what lies
    // below it: every row at or below its top maps to itself, and the muscle above it, all of it,
    // fills the 4 mm between the face and the bone.
    Flat f;
    const float skin = -12.0f, bone_top = skin + 16.0f, bone_bottom = bone_top + 10.0f;
    io::Volume labels = f.grid;
    for (std::size_t k = 0; k < labels.size[2]; ++k)
        for (std::size_t j = 0; j < labels.size[1]; ++j)
            for (std::size_t i = 0; i < labels.size[0]; ++i) {
                const double y = labels.index_to_world(glm::dvec3(double(i), double(j), double(k))).y;
                const bool bone = y >= bone_top && y < bone_bottom;
                labels.data[labels.index(i, j, k)] = std::uint8_t(bone ? Tissue::bone_cortex : Tissue::muscle);
            }
    const TissueTable tissues = tissue_mechanics({});
    ASSERT_LT(tissues[int(Tissue::muscle)].max_strain * 16.0f, -skin);  // the premise: the muscle alone cannot take it
    EchoFrame frame;
    frame.columns.assign(f.plane.columns, {skin, -skin});
    frame.skin_pressure_kpa = 40;
    const KernelParams k = make_kernel_params(f.grid, f.plane, frame, {}, {}, true);
    const auto map = deform_cpu(&labels, frame.columns, tissues, k.deform);
    for (std::uint32_t c : {0u, 40u, 79u}) {  // at the face's edges too, where less of the pressure reaches
        double last = -1e9;
        for (std::uint32_t r = 0; r < f.plane.rows; ++r) {
            const double y = (r + 0.5) * f.plane.pixel_y_mm(), source = map[r * f.plane.columns + c].x;
            if (y >= bone_top + 0.5) {
                EXPECT_NEAR(source, y, 0.05) << "column " << c << ", row " << r;
            }
            if (y < bone_top - 0.5) {
                EXPECT_TRUE(source >= skin && source < bone_top) << "column " << c << ", row " << r << ": " << source;
            }
            EXPECT_GE(source, last) << "column " << c << ", row " << r;  // nothing folded
            last = source;
        }
        // the first row (0.25 mm under the face) shows the skin: 16 mm in 4 mm is 1 mm of tissue in
        // 0.25 mm of image on average, so none of the muscle went off the top
        EXPECT_LT(map[c].x, skin + 1.5) << "column " << c;
    }
}

// Muscle with a vein's lumen 10 mm across, centred 20 mm under the skin, pressed 6 mm in and hard
// enough to close it: the map of the Flat plane (0.5 mm pixels and columns).
struct PressedVein : Flat {
    static constexpr double kCentreY = 14, kRadius = 5;
    static constexpr float kSkinMm = 6, kPressureKpa = 30;  // the skin 6 mm above the face, pressed onto it
    std::vector<glm::vec2> map;
    // `pressure_kpa`: the face's; `pixels`: the plane's columns (as many as the map has: the voxels') and rows
    explicit PressedVein(const TissueTable& tissues, bool vein = true, float pressure_kpa = kPressureKpa, glm::uvec2 pixels = {80, 100})
    {
        plane.columns = pixels.x;
        plane.rows = pixels.y;
        io::Volume labels = grid;
        std::fill(labels.data.begin(), labels.data.end(), std::uint8_t(Tissue::muscle));
        for (std::size_t k = 0; k < labels.size[2]; ++k)
            for (std::size_t j = 0; j < labels.size[1]; ++j)
                for (std::size_t i = 0; i < labels.size[0]; ++i) {
                    const glm::dvec3 p = labels.index_to_world(glm::dvec3(double(i), double(j), double(k)));
                    if (vein && std::hypot(p.x, p.y - kCentreY) < kRadius) labels.data[labels.index(i, j, k)] = std::uint8_t(Tissue::vein_lumen);
                }
        EchoFrame frame;
        frame.columns.assign(plane.columns, {-kSkinMm, kSkinMm});
        frame.skin_pressure_kpa = pressure_kpa;
        const KernelParams k = make_kernel_params(grid, plane, frame, {}, {}, true);
        map = deform_cpu(&labels, frame.columns, tissues, k.deform);
    }
    double x_of(std::uint32_t c) const { return (c + 0.5) * plane.pixel_x_mm() - 20; }
    // where image pixel (c, r) comes from [mm], and the gain it gets [dB]
    double source(std::uint32_t c, std::uint32_t r) const { return map[std::size_t(r) * plane.columns + c].x; }
    double gain(std::uint32_t c, std::uint32_t r) const { return map[std::size_t(r) * plane.columns + c].y; }
};

TEST(DeformCpu, AClosingVeinsWallsMeet)
{
    const TissueTable tissues = tissue_mechanics({});
    const PressedVein v(tissues);
    // where the pressure that reaches the lumen's floor closes it fully, no pixel comes from inside
    // it, but within a walk step and a voxel (0.5 mm each: where the labels put the wall) of a wall
    int closed_columns = 0;
    for (std::uint32_t c = 0; c < v.plane.columns; ++c) {
        const double x = v.x_of(c);
        if (std::abs(x) >= 0.9 * v.kRadius) continue;
        const double half = std::sqrt(v.kRadius * v.kRadius - x * x);
        const float floor_depth = float(v.kSkinMm + v.kCentreY + half);
        const float reaching = v.kPressureKpa * kernels::face_influence(float(x), floor_depth, 40, 10);
        if (kernels::lumen_closure(tissues[int(Tissue::vein_lumen)], reaching, 0) < 0.999f) continue;
        ++closed_columns;
        for (std::uint32_t r = 0; r < v.plane.rows; ++r) {
            const double s = v.source(c, r);
            EXPECT_FALSE(s > v.kCentreY - half + 1.0 && s < v.kCentreY + half - 1.0)
                << "column at " << x << " mm, row " << r << ": from " << s << " mm, the lumen " << v.kCentreY - half << ".." << v.kCentreY + half;
        }
    }
    EXPECT_GT(closed_columns, 12);  // most of the vein's 18 columns
}

TEST(DeformCpu, TheTissueAboveAClosingVeinSinksAndDragsItsNeighboursAlong)
{
    const PressedVein v(tissue_mechanics({})), none(tissue_mechanics({}), false);
    // the image row that, without the vein, shows the tissue 2 mm above its top: how much shallower
    // its tissue comes from with the vein, i.e. how far it sank into the closed lumen, across the image
    std::uint32_t r = 0;
    while (none.source(v.plane.columns / 2, r) < v.kCentreY - v.kRadius - 2) ++r;
    std::vector<double> sank(v.plane.columns);
    for (std::uint32_t c = 0; c < v.plane.columns; ++c) sank[c] = none.source(c, r) - v.source(c, r);

    const auto at = [&](double x) { return sank[std::uint32_t((x + 20) / v.plane.pixel_x_mm())]; };
    EXPECT_GT(at(0), 1.0);  // above the vein: sunk by mm
    // beside it, dragged along, less the further out; far out, not at all
    EXPECT_GT(at(v.kRadius + 2), 0.1 * at(0));
    EXPECT_LT(at(v.kRadius + 2), 0.8 * at(0));
    EXPECT_LT(at(v.kRadius + 6), at(v.kRadius + 2));
    EXPECT_LT(std::abs(at(-15)), 0.05 * at(0));
    // and no seam: neighbouring columns (0.5 mm apart) differ by a fraction of the sinking
    for (std::uint32_t c = 1; c < v.plane.columns; ++c) EXPECT_LT(std::abs(sank[c] - sank[c - 1]), 0.15 * at(0)) << "at " << v.x_of(c) << " mm";
}

TEST(DeformCpu, TheGainUnderAClosedVeinFadesOutOverTheBeamsWidth)
{
    const TissueTable tissues = tissue_mechanics({});
    const PressedVein v(tissues);
    const kernels::DeformParams d = make_kernel_params(v.grid, v.plane, {}, {}, {}, true).deform;
    // what closing a length of blood takes from what lies below it, per mm of the closed length
    const double per_mm = -kernels::closure_gain_db(1.0f, 1.0f, tissues[int(Tissue::vein_lumen)], d.tgc_db_cm_mhz, d.frequency_mhz);
    ASSERT_GT(per_mm, 0.1);
    // the image row that shows the tissue 5 mm under the vein's floor at its middle
    const std::uint32_t middle = v.plane.columns / 2;
    std::uint32_t r = 0;
    while (v.source(middle, r) < v.kCentreY + v.kRadius + 5) ++r;
    std::vector<double> gain(v.plane.columns);
    for (std::uint32_t c = 0; c < v.plane.columns; ++c) gain[c] = -v.map[std::size_t(r) * v.plane.columns + c].y;

    // The expectation, independent of the kernel's walk: each lateral position loses the vein's
    // chord there (a closed column loses all of it), spread across the beam by a Gaussian of
    // DEFORM_GAIN_BLUR_MM, integrated finely (not over the map's columns)
    const double sigma = DEFORM_GAIN_BLUR_MM;
    const auto chord = [&](double x) { return std::abs(x) < v.kRadius ? 2.0 * std::sqrt(v.kRadius * v.kRadius - x * x) : 0.0; };
    const auto expected = [&](double x) {
        double sum = 0, weights = 0;
        for (double u = -4 * sigma; u <= 4 * sigma; u += 0.01) {
            const double w = std::exp(-0.5 * u * u / (sigma * sigma));
            sum += w * chord(x + u) * per_mm;
            weights += w;
        }
        return sum / weights;
    };
    const double full = 2 * v.kRadius * per_mm;
    EXPECT_NEAR(gain[middle], full, 0.05 * full);  // the middle loses the whole enhancement
    // across, the expectation within 15 % of the whole (the labels' voxels and the columns are
    // 0.5 mm: here 0.11), and no step between neighbouring columns larger than the beam's fade makes
    // (here 0.21; each column on its own stepped 0.5 at the vein's edge: a line down the image,
    // 0.29 off the expectation)
    for (std::uint32_t c = 0; c < v.plane.columns; ++c) {
        EXPECT_NEAR(gain[c], expected(v.x_of(c)), 0.15 * full) << "at " << v.x_of(c) << " mm";
        if (c > 0) {
            EXPECT_LT(std::abs(gain[c] - gain[c - 1]), 0.3 * full) << "at " << v.x_of(c) << " mm";
        }
    }
}

TEST(DeformCpu, AClosedVeinsWallsMeetAsOneBrightLine)
{
    const TissueTable tissues = tissue_mechanics({});
    const PressedVein v(tissues, true, PressedVein::kPressureKpa, {80, 500});  // 0.1 mm rows
    const double py = v.plane.pixel_y_mm();
    // down the middle column: where the map's source jumps over the closed lumen, the walls meet
    const std::uint32_t c = v.plane.columns / 2;
    std::uint32_t meet = 0;
    for (std::uint32_t r = 1; r < v.plane.rows && meet == 0; ++r)
        if (v.source(c, r) - v.source(c, r - 1) > v.kRadius) meet = r;
    ASSERT_GT(meet, 0u) << "the vein did not close";
    // the walls' one echo: a gain at the meeting point (the pixel either side of it within 0.1 mm of
    // it gets at least two thirds of the line's peak), over what the column has 1 mm above and below
    const double line = std::max(v.gain(c, meet - 1), v.gain(c, meet)), above = v.gain(c, meet - 10), under = v.gain(c, meet + 10);
    EXPECT_GT(line - std::max(above, under), 0.66 * DEFORM_SEAM_DB);
    // and nowhere else in the column: half a millimetre or more from the meeting point, no row is
    // brighter than the rows around it (the gain only falls, where closed lumens lie above)
    for (std::uint32_t r = 1; r < v.plane.rows; ++r) {
        if (std::abs((double(r) - double(meet) + 0.5) * py) < 0.5) continue;
        EXPECT_LE(v.gain(c, r), v.gain(c, r - 1) + 1e-4) << "row " << r << ", the walls meet at row " << meet;
    }

    // a vein the probe closes only partly keeps its lumen between its walls, dark: no line
    const PressedVein open(tissues, true, 5.0f, {80, 500});
    int lumen_rows = 0;  // the rows of the middle column that show the lumen
    for (std::uint32_t r = 0; r < open.plane.rows; ++r)
        lumen_rows += std::abs(open.source(c, r) - open.kCentreY) < open.kRadius - 0.5 ? 1 : 0;
    ASSERT_GT(lumen_rows * py, 1.0);                             // open by more than a millimetre
    ASSERT_LT(lumen_rows * py, 0.9 * 2 * (open.kRadius - 0.5));  // yet pressed
    for (std::uint32_t r = 1; r < open.plane.rows; ++r) EXPECT_LE(open.gain(c, r), open.gain(c, r - 1) + 1e-4) << "row " << r;
}

TEST(SliceCpu, BetweenMapColumnsTheSourceNeverFallsIntoAClosedLumen)
{
    using kernels::map_between;
    // two map columns either side of a closed lumen's end: one maps a row to the wall above the
    // lumen (12 mm), the other to the wall below (17 mm); a pixel between them takes the nearer
    // one's source (a lerp would put it at 14.5 mm, inside the lumen), and the gain lerped (the
    // beam's, smooth across: the walls' echo runs from one column's meeting point to the next's)
    const glm::vec2 above(12.0f, 0.0f), below(17.0f, -3.0f);
    EXPECT_EQ(map_between(above, below, 0.3f).x, above.x);
    EXPECT_NEAR(map_between(above, below, 0.3f).y, -0.9f, 1e-6f);
    EXPECT_EQ(map_between(above, below, 0.7f).x, below.x);
    EXPECT_NEAR(map_between(above, below, 0.7f).y, -2.1f, 1e-6f);
    // columns of a smooth field are lerped
    const glm::vec2 a(12.0f, 0.0f), b(12.4f, -1.0f);
    EXPECT_NEAR(map_between(a, b, 0.25f).x, 12.1f, 1e-6f);
    EXPECT_NEAR(map_between(a, b, 0.25f).y, -0.25f, 1e-6f);
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

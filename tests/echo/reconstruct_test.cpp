#include "echo/reconstruct.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "echo/slice_cpu.hpp"
#include "echo/sweep.hpp"

namespace echosim::echo {
namespace {

// a frame in the plane z = z0: pixel (c, r) at (c, r, z0) mm
glm::dmat4 flat_frame(double z0)
{
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(0, 0, z0, 1);
    return m;
}

TEST(Reconstructor, NearestSplatPutsPixelsInTheirVoxels)
{
    ReconstructOptions o;
    o.voxel_mm = 1.0;
    o.splat = Splat::nearest;
    Reconstructor r({0, 0, 0}, {9, 9, 4}, o);
    std::vector<std::uint8_t> px(100);
    for (std::size_t k = 0; k < px.size(); ++k) px[k] = std::uint8_t(k);
    r.insert(px, {}, 10, 10, flat_frame(2.0));
    const io::Volume v = r.volume();
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(3, 7, 2)], 73);  // column 3, row 7
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(3, 7, 1)], 0);   // not reached
    EXPECT_EQ(r.filled_voxels(), 100u);
}

TEST(Reconstructor, MeanAndMaxCompounding)
{
    for (Compounding c : {Compounding::mean, Compounding::max}) {
        ReconstructOptions o;
        o.voxel_mm = 1.0;
        o.splat = Splat::nearest;
        o.compounding = c;
        Reconstructor r({0, 0, 0}, {4, 4, 4}, o);
        r.insert(std::vector<std::uint8_t>(25, 100), {}, 5, 5, flat_frame(2.0));
        r.insert(std::vector<std::uint8_t>(25, 200), {}, 5, 5, flat_frame(2.0));
        const io::Volume v = r.volume();
        EXPECT_EQ(v.as<std::uint8_t>()[v.index(1, 1, 2)], c == Compounding::mean ? 150 : 200);
    }
}

TEST(Reconstructor, TrilinearSplatSpreadsBetweenVoxels)
{
    ReconstructOptions o;
    o.voxel_mm = 1.0;
    Reconstructor r({0, 0, 0}, {9, 9, 4}, o);
    r.insert(std::vector<std::uint8_t>(100, 80), {}, 10, 10, flat_frame(1.5));  // half-way between two planes
    const io::Volume v = r.volume();
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(4, 4, 1)], 80);
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(4, 4, 2)], 80);
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(4, 4, 3)], 0);
}

TEST(Reconstructor, HolesBetweenFramesAreFilledFromBothSides)
{
    ReconstructOptions o;
    o.voxel_mm = 1.0;
    o.splat = Splat::nearest;
    Reconstructor r({0, 0, 0}, {9, 9, 20}, o);
    r.insert(std::vector<std::uint8_t>(100, 40), {}, 10, 10, flat_frame(4.0));
    r.insert(std::vector<std::uint8_t>(100, 120), {}, 10, 10, flat_frame(8.0));
    const int passes = r.fill_holes();
    EXPECT_GE(passes, 2);
    const io::Volume v = r.volume();
    const auto at = [&](std::size_t k) { return int(v.as<std::uint8_t>()[v.index(5, 5, k)]); };
    // the front moves in from both frames: the voxels next to a frame take its value, the one in
    // the middle, reached from both at once, their mean; nothing outside their range
    EXPECT_EQ(at(5), 40);
    EXPECT_EQ(at(6), 80);
    EXPECT_EQ(at(7), 120);
    EXPECT_EQ(at(20), 0) << "beyond max_fill_mm (5 mm) of data nothing is invented";
}

TEST(Reconstructor, RefusesAVolumeOverTheMemoryBudget)
{
    ReconstructOptions o;
    o.voxel_mm = 0.1;
    o.memory_budget_bytes = 64ull << 20;
    try {
        Reconstructor r({0, 0, 0}, {100, 100, 100}, o);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("over the memory budget of 64 MiB"), std::string::npos) << e.what();
    }
    EXPECT_GT(reconstruction_bytes({100, 100, 100}, 0.1), 1ull << 30);

    // a grid whose voxel count wraps 64 bits (a file's numbers can ask for it) is refused, not
    // allocated at its wrapped size
    VoxelGrid wraps;
    wraps.size = {std::size_t(1) << 22, std::size_t(1) << 22, std::size_t(1) << 22};  // 2^66 voxels
    EXPECT_EQ(wraps.voxel_count(), UINT64_MAX);
    EXPECT_THROW(Reconstructor(wraps, ReconstructOptions{}), std::runtime_error);
    // and so is a box too large to grid at all, or a NaN in it
    EXPECT_THROW(box_grid({0, 0, 0}, {1e300, 1, 1}, 0.1), std::invalid_argument);
    EXPECT_THROW(box_grid({0, 0, 0}, {std::nan(""), 1, 1}, 0.1), std::invalid_argument);
}

// The whole chain on the phantom: a sweep, its reconstruction, and slices of it at poses the sweep
// did not visit, against images synthesised directly there.
class PhantomReconstruction : public testing::Test {
protected:
    static void SetUpTestSuite()
    {
        leg_ = new scene::LegModel();
        phantom_ = new Phantom(*leg_, Case::healthy);
        SweepOptions o;
        o.frames = 90;
        o.u_from = 0.3f;
        o.u_to = 0.7f;  // about 48 mm of thigh, a frame every 0.54 mm
        o.spec.pixel_mm = 0.15;
        o.spec.depth_mm = 45;
        spec_ = o.spec;
        const PhantomMedium medium(*phantom_);
        const TrackedSweep sweep = make_sweep(*leg_, medium, o);
        const SweepBox box = sweep_box(sweep.sweep);
        ReconstructOptions ro;
        ro.voxel_mm = 0.3;
        Reconstructor rec(box.lo, box.hi, ro, box.axes);
        for (std::size_t f = 0; f < sweep.sweep.frames.size(); ++f)
            rec.insert({sweep.sweep.frame_pixels(f), sweep.sweep.frame_bytes()}, {sweep.labels.data() + f * sweep.sweep.frame_bytes(), sweep.sweep.frame_bytes()},
                       sweep.sweep.width, sweep.sweep.height, sweep.sweep.frames[f].image_to_reference);
        rec.fill_holes();
        volume_ = new io::Volume(rec.volume());
        labels_ = new io::Volume(rec.labels());
    }
    static void TearDownTestSuite()
    {
        delete labels_;
        delete volume_;
        delete phantom_;
        delete leg_;
    }
    static inline scene::LegModel* leg_ = nullptr;
    static inline Phantom* phantom_ = nullptr;
    static inline io::Volume* volume_ = nullptr;
    static inline io::Volume* labels_ = nullptr;
    static inline ScanSpec spec_;
};

// centroid and equivalent diameter [mm] of one tissue in an image
std::pair<glm::dvec2, double> blob(const std::vector<std::uint8_t>& labels, Tissue t, const ScanSpec& spec)
{
    glm::dvec2 sum(0.0);
    double n = 0;
    for (std::uint32_t r = 0; r < spec.rows(); ++r)
        for (std::uint32_t c = 0; c < spec.columns(); ++c)
            if (labels[std::size_t(r) * spec.columns() + c] == std::uint8_t(t)) sum += glm::dvec2(c, r), n += 1;
    return {sum / std::max(n, 1.0) * spec.pixel_mm, 2.0 * std::sqrt(n / std::numbers::pi) * spec.pixel_mm};
}

TEST_F(PhantomReconstruction, SlicesMatchDirectImagesAtPosesNotInTheSweep)
{
    const PhantomMedium medium(*phantom_);
    for (float u : {0.41f, 0.5037f, 0.59f}) {
        const Pose pose = leg_->probe_rest_pose(u, 0.5f);
        const BModeImage direct = synthesize(medium, pose, spec_);
        const std::vector<std::uint8_t> sliced = slice_grey(*volume_, pose, spec_);
        std::vector<std::uint8_t> inside(sliced.size());
        for (std::size_t k = 0; k < sliced.size(); ++k) inside[k] = direct.labels[k] != std::uint8_t(Tissue::outside);
        const double ncc = normalised_cross_correlation(direct.pixels, sliced, inside);
        const double psnr = psnr_db(direct.pixels, sliced, inside);
        std::printf("slice at u = %.4f: NCC %.3f, PSNR %.1f dB\n", double(u), ncc, psnr);
        // a 0.3 mm voxel map of 0.15 mm speckle keeps the anatomy and part of the speckle
        EXPECT_GT(ncc, 0.55) << "u " << u;
        EXPECT_GT(psnr, 18.0) << "u " << u;
    }
}

TEST_F(PhantomReconstruction, VesselsAreRecoveredWithinTwoVoxels)
{
    const PhantomMedium medium(*phantom_);
    const Pose pose = leg_->probe_rest_pose(0.5037f, 0.5f);
    const BModeImage direct = synthesize(medium, pose, spec_);
    const std::vector<std::uint8_t> sliced = slice_labels(*labels_, pose, spec_);
    for (Tissue t : {Tissue::vein_lumen, Tissue::artery_lumen}) {
        const auto [c_true, d_true] = blob(direct.labels, t, spec_);
        const auto [c_rec, d_rec] = blob(sliced, t, spec_);
        EXPECT_GT(d_true, 6.0) << tissue_name(t);
        EXPECT_LT(glm::length(c_rec - c_true), 2 * 0.3) << tissue_name(t);
        EXPECT_NEAR(d_rec, d_true, 2 * 0.3) << tissue_name(t);
    }
}

}  // namespace
}  // namespace echosim::echo

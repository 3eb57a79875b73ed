#include "echo/reconstruct.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

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

// The hole filling as documented, written plainly (one voxel at a time, its 26 neighbours by
// index): each pass gives every empty voxel next to a filled one the distance-weighted mean of its
// filled neighbours (weight 1/distance in voxels) and the label of its nearest one (the first in
// z, y, x order at that distance), from the values the pass started with; up to max_fill_mm.
void fill_plainly(std::vector<float>& value, std::vector<std::uint8_t>& label, std::vector<bool>& filled, const std::array<long, 3>& n,
                  int passes)
{
    for (int pass = 0; pass < passes; ++pass) {
        std::vector<float> next_value = value;
        std::vector<std::uint8_t> next_label = label;
        std::vector<bool> next_filled = filled;
        for (long k = 0; k < n[2]; ++k)
            for (long j = 0; j < n[1]; ++j)
                for (long i = 0; i < n[0]; ++i) {
                    const long at = (k * n[1] + j) * n[0] + i;
                    if (filled[std::size_t(at)]) continue;
                    double sum = 0, wsum = 0;
                    float nearest = 1e9f;
                    std::uint8_t l = 0;
                    for (long dz = -1; dz <= 1; ++dz)
                        for (long dy = -1; dy <= 1; ++dy)
                            for (long dx = -1; dx <= 1; ++dx) {
                                const long x = i + dx, y = j + dy, z = k + dz;
                                if ((dx | dy | dz) == 0 || x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) continue;
                                const std::size_t m = std::size_t((z * n[1] + y) * n[0] + x);
                                if (!filled[m]) continue;
                                const float d2 = float(dx * dx + dy * dy + dz * dz);
                                const double w = 1.0 / std::sqrt(double(d2));
                                sum += w * value[m];
                                wsum += w;
                                if (d2 < nearest) nearest = d2, l = label[m];
                            }
                    if (wsum == 0) continue;
                    next_value[std::size_t(at)] = float(sum / wsum);
                    if (next_label[std::size_t(at)] == 0) next_label[std::size_t(at)] = l;
                    next_filled[std::size_t(at)] = true;
                }
        value.swap(next_value);
        label.swap(next_label);
        filled.swap(next_filled);
    }
}

// fill_holes keeps a front of voxels to fill rather than visiting every voxel each pass: the volume
// and the labels must be the plain fill's, byte for byte (frames tilted and far apart, labels in
// patches)
TEST(Reconstructor, HoleFillingIsThePlainFill)
{
    ReconstructOptions o;
    o.voxel_mm = 1.0;
    o.splat = Splat::nearest;
    o.compounding = Compounding::max;  // whole values in the filled voxels, as the volume shows them
    o.max_fill_mm = 4.0;
    const auto frame = [](double z0, double tilt) {
        glm::dmat4 m(1.0);
        m[1] = glm::dvec4(0, std::cos(tilt), std::sin(tilt), 0);  // rows lean along z
        m[3] = glm::dvec4(0.3, 0.2, z0, 1);
        return m;
    };
    const auto make = [&] {
        Reconstructor r({0, 0, 0}, {23, 17, 30}, o);
        for (int f = 0; f < 4; ++f) {
            std::vector<std::uint8_t> px(24 * 16), labels(24 * 16);
            for (std::size_t q = 0; q < px.size(); ++q) {
                px[q] = std::uint8_t(1 + (q * 37 + std::size_t(f) * 11) % 250);  // never 0: filled voxels are > 0
                labels[q] = std::uint8_t(1 + (q / 40 + std::size_t(f)) % 5);
            }
            r.insert(px, labels, 24, 16, frame(3.0 + 7.5 * f, 0.2 * f));
        }
        return r;
    };
    Reconstructor before = make();
    const io::Volume raw = before.volume(), raw_labels = before.labels();
    std::vector<float> value(raw.voxel_count());
    std::vector<std::uint8_t> label(raw_labels.as<std::uint8_t>(), raw_labels.as<std::uint8_t>() + raw_labels.voxel_count());
    std::vector<bool> filled(value.size());
    for (std::size_t q = 0; q < value.size(); ++q) value[q] = raw.as<std::uint8_t>()[q], filled[q] = value[q] > 0;
    const std::array<long, 3> n{long(raw.size[0]), long(raw.size[1]), long(raw.size[2])};
    fill_plainly(value, label, filled, n, 4);
    std::size_t holes_filled = 0;
    for (std::size_t q = 0; q < value.size(); ++q) holes_filled += filled[q] && raw.as<std::uint8_t>()[q] == 0;
    ASSERT_GT(holes_filled, 1000u);

    Reconstructor r = make();
    EXPECT_EQ(r.fill_holes(), 4);
    const io::Volume v = r.volume(), l = r.labels();
    std::size_t differ = 0, labels_differ = 0;
    for (std::size_t q = 0; q < value.size(); ++q) {
        differ += v.as<std::uint8_t>()[q] != std::uint8_t(std::clamp(value[q] + 0.5f, 0.0f, 255.0f));
        labels_differ += l.as<std::uint8_t>()[q] != label[q];
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(labels_differ, 0u);
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

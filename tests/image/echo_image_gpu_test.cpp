// The echographic image's three kernels on the GPU (lavapipe, validation on) against their CPU
// twins, stage by stage, on the same frames: at rest, pressed by the simulated tissue over the
// femoral vessels, and pressed without labels (the paper's linear deformation). Tolerances: the
// deform map's source depth within 0.02 mm at 99.9 % of the pixels (the GPU's exp2, atan and sqrt
// differ from the C library's in the last bits, which can move a lumen's closure threshold a hair);
// the slice's grey within 1.5 levels (the sampler's filter weights are fixed point on some
// devices) at 99.9 %, and the displayed grey within 3 levels at 99.5 %; labels equal at 99.9 %.
#include "image/echo_image_gpu.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include <gtest/gtest.h>

#include "echo/echo_image_cpu.hpp"
#include "echo/echo_test_volumes.hpp"
#include "session/session.hpp"
#include "image/fraction_close.hpp"
#include "test_gpu.hpp"

namespace echosim::image {
namespace {

using test::fraction_close;

void expect_twins(const echo::EchoImage& gpu, const echo::EchoImage& cpu, const char* what)
{
    SCOPED_TRACE(what);
    ASSERT_EQ(gpu.columns, cpu.columns);
    ASSERT_EQ(gpu.rows, cpu.rows);
    ASSERT_EQ(gpu.map.size(), cpu.map.size());
    if (!cpu.map.empty()) {
        std::vector<float> gy, cy, g_gain, c_gain;  // the source depths and the gains
        for (std::size_t i = 0; i < cpu.map.size(); i += 2) {
            gy.push_back(gpu.map[i]);
            cy.push_back(cpu.map[i]);
            g_gain.push_back(gpu.map[i + 1]);
            c_gain.push_back(cpu.map[i + 1]);
        }
        EXPECT_GE(fraction_close(gy, cy, [](float a, float b) { return std::abs(a - b) <= 0.02f; }), 0.999);
        // (the closed lumens' gains across the beam and their walls' line: a few pixels each, which
        // the displayed image's 0.5 % allowance below would not notice)
        EXPECT_GE(fraction_close(g_gain, c_gain, [](float a, float b) { return std::abs(a - b) <= 0.05f; }), 0.9995);
        const auto lit = [](const std::vector<float>& gains) { return std::count_if(gains.begin(), gains.end(), [](float g) { return g > 6.0f; }); };
        EXPECT_LE(std::abs(lit(g_gain) - lit(c_gain)), std::max<long>(2, lit(c_gain) / 50)) << "pixels on a closed vein's walls' line";
    }
    EXPECT_GE(fraction_close(gpu.grey, cpu.grey, [](float a, float b) { return std::abs(a - b) <= 1.5f; }), 0.999);
    EXPECT_GE(fraction_close(gpu.rgba, cpu.rgba, [](std::uint32_t a, std::uint32_t b) { return std::abs(int(a & 0xff) - int(b & 0xff)) <= 3; }),
              0.995);
    for (std::size_t i = 0; i < gpu.rgba.size(); ++i) ASSERT_EQ(gpu.rgba[i] >> 24, 255u) << "pixel " << i << " is not opaque";
    EXPECT_EQ(gpu.labels.size(), cpu.labels.size());
    if (!cpu.labels.empty()) {
        EXPECT_GE(fraction_close(gpu.labels, cpu.labels, [](std::uint8_t a, std::uint8_t b) { return a == b; }), 0.999);
    }
}

TEST(EchoImageGpu, EachKernelMatchesItsCpuTwin)
{
    session::Session s;
    const scene::LegModel leg;
    const test::LabelledVolume v = test::phantom_volume(leg, echo::Case::healthy, s.probe().rest);
    const auto [rest, pressed] = test::rest_and_pressed(s, 12.0);
    ASSERT_GT(s.view().probe_force_N, 1.0);
    echo::ScannerSettings scanner;
    scanner.gain_db = 4;
    scanner.tgc_db = {-3, -2, -1, 0, 1, 2, 3, 4};

    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        gpu::CommandPool pool(ctx);
        const auto cpu = [&](const echo::EchoFrame& f, bool labels, const echo::ImagePlane& plane) {
            return echo::render_echo_cpu(v.grey, labels ? &v.labels : nullptr, plane, f, scanner, s.patient(), labels);
        };
        // the live plane reads a deform map coarser than its pixels (a fraction of a map column
        // each); a plane as coarse as the map reads one map column a pixel (map_step 1)
        echo::ImagePlane coarse = s.image_plane();
        coarse.columns = 100;
        coarse.rows = 125;
        session::Session coarse_session(session::SessionOptions{.image = coarse});
        coarse_session.press_and_settle(coarse_session.probe().rest, 12.0);
        const echo::EchoFrame coarse_frame = *coarse_session.view().echo;
        // both configurations: a GPU's (the grey levels through the trilinear sampler, the deform's
        // map pass reading storage) and lavapipe's (the packed volume, the map pass reading texels)
        for (const GreyLayout layout : {GreyLayout::sampler, GreyLayout::packed}) {
            SCOPED_TRACE(layout == GreyLayout::packed ? "packed volume, texel reads" : "R8 volume, trilinear sampler, storage reads");
            const DeformReads reads = layout == GreyLayout::packed ? DeformReads::texels : DeformReads::storage;
            const auto labelled = std::make_shared<const EchoVolumeGpu>(pool, v.grey, &v.labels, layout);
            const auto bare = std::make_shared<const EchoVolumeGpu>(pool, v.grey, nullptr, layout);
            ASSERT_EQ(labelled->packed(), layout == GreyLayout::packed);
            EchoImageGpu with_labels(ctx, labelled, s.image_plane(), s.patient(), reads);
            EchoImageGpu without(ctx, bare, s.image_plane(), s.patient(), reads);
            with_labels.scanner() = scanner;
            without.scanner() = scanner;
            expect_twins(with_labels.render(pool, rest, true), cpu(rest, true, s.image_plane()), "at rest");
            const echo::EchoImage pressed_cpu = cpu(pressed, true, s.image_plane());
            // (pressed enough to close the vein: its walls' line is drawn, the gain compared above)
            bool line = false;
            for (std::size_t i = 1; i < pressed_cpu.map.size(); i += 2) line = line || pressed_cpu.map[i] > 6.0f;
            EXPECT_TRUE(line) << "no closed vein's walls in the pressed image";
            expect_twins(with_labels.render(pool, pressed, true), pressed_cpu, "pressed 12 mm");
            expect_twins(without.render(pool, pressed), cpu(pressed, false, s.image_plane()), "pressed, no labels");
            EchoImageGpu coarse_image(ctx, labelled, coarse, s.patient(), reads);
            coarse_image.scanner() = scanner;
            const echo::EchoImage coarse_pressed = coarse_image.render(pool, coarse_frame, true);
            ASSERT_EQ(coarse_pressed.map_columns, coarse.columns) << "the coarse plane's map is as fine as its pixels";
            expect_twins(coarse_pressed, cpu(coarse_frame, true, coarse), "pressed 12 mm, 100 x 125 pixels");
            // the same frame twice: the GPU is deterministic
            EXPECT_EQ(with_labels.render(pool, pressed).rgba, with_labels.render(pool, pressed).rgba);
        }
    }
    EXPECT_EQ(messages->load(), 0u);
}

// The GPU's timestamps between the stages (enable_stage_timing): a frame names the stages it ran,
// in order, each with some time, together no more than the frame took from recording to its end;
// the deform's spread pass only where the map reads storage (a GPU's way), none at rest.
TEST(EchoImageGpu, StageTimesNameTheStagesAFrameRan)
{
    session::Session s;
    const scene::LegModel leg;
    const test::LabelledVolume v = test::phantom_volume(leg, echo::Case::healthy, s.probe().rest);
    const auto [rest, pressed] = test::rest_and_pressed(s, 12.0);
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        gpu::CommandPool pool(ctx);
        const auto volume = std::make_shared<const EchoVolumeGpu>(pool, v.grey, &v.labels, GreyLayout::sampler);
        const auto names = [](const std::vector<std::pair<std::string, double>>& times) {
            std::vector<std::string> n;
            for (const auto& t : times) n.push_back(t.first);
            return n;
        };
        for (const DeformReads reads : {DeformReads::storage, DeformReads::texels}) {
            SCOPED_TRACE(reads == DeformReads::storage ? "storage reads" : "texel reads");
            EchoImageGpu pipeline(ctx, volume, s.image_plane(), s.patient(), reads);
            EXPECT_TRUE(pipeline.stage_times(0).empty()) << "no times before timing is enabled";
            pipeline.enable_stage_timing(ctx);
            const auto start = std::chrono::steady_clock::now();
            (void)pipeline.render(pool, pressed);
            const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            const auto times = pipeline.stage_times(0);
            std::vector<std::string> expected{"deform: solve", "deform: map", "slice+post", "display copy"};
            if (reads == DeformReads::storage) expected.insert(expected.begin() + 1, "deform: spread");
            EXPECT_EQ(names(times), expected);
            double sum = 0;
            for (const auto& [name, ms] : times) {
                EXPECT_GT(ms, 0.0) << name;
                sum += ms;
            }
            EXPECT_LE(sum, wall_ms);
            (void)pipeline.render(pool, rest);
            EXPECT_EQ(names(pipeline.stage_times(0)), (std::vector<std::string>{"slice+post", "display copy"})) << "at rest";
        }
    }
    EXPECT_EQ(messages->load(), 0u);
}

// The packed layout's tiles (slice_bindings.h, packed_texel) fold into rows between past
// SLICE_TILES_A_ROW tiles (512 voxels of x): a plane turned 20 degrees against a volume 603
// voxels wide, its x ending in a part tile and its y (10) not a multiple of 4, crosses the fold, part
// tiles and every z layer; the packed volume's slice must be its CPU twin's everywhere.
TEST(EchoImageGpu, APackedVolumeWiderThanAnImageRowSlicesAsItsCpuTwin)
{
    session::Session s;
    const Pose rest = s.probe().rest;
    echo::EchoFrame frame = *s.view().echo;
    frame.columns.clear();
    io::Volume grey = io::make_volume({603, 10, 7}, io::VoxelType::uint8);
    std::mt19937 random(7);
    for (std::uint8_t& v : grey.data) v = std::uint8_t(random() % 256u);
    // 0.08 mm across (48 mm), 6 mm along the beam (60 mm), 3 mm in elevation, about the image's middle
    const glm::quat turn = glm::angleAxis(glm::radians(20.0f), rest.axis_y()) * glm::angleAxis(glm::radians(3.0f), rest.axis_x());
    grey.directions = glm::dmat3(glm::mat3_cast(turn * rest.orientation)) * glm::dmat3(glm::dvec3(0.08, 0, 0), glm::dvec3(0, 6, 0),
                                                                                       glm::dvec3(0, 0, 3));
    const glm::dvec3 centre = glm::dvec3(rest.position) + 25.0 * glm::dvec3(rest.axis_y());
    grey.origin = centre - grey.directions * glm::dvec3(301, 4.5, 3);

    gpu::Context ctx(test::lavapipe_options());
    gpu::CommandPool pool(ctx);
    const auto volume = std::make_shared<const EchoVolumeGpu>(pool, grey, nullptr, GreyLayout::packed);
    EXPECT_EQ(volume->grey().extent().width, 2048u);
    EXPECT_EQ(volume->grey().extent().height, 2u * 3u) << "two folds, three rows each";
    EchoImageGpu image(ctx, volume, s.image_plane(), s.patient());
    const echo::EchoImage gpu = image.render(pool, frame);
    const echo::EchoImage cpu = echo::render_echo_cpu(grey, nullptr, s.image_plane(), frame, image.scanner(), s.patient());
    ASSERT_EQ(gpu.grey.size(), cpu.grey.size());
    std::size_t inside = 0, apart = 0;
    for (std::size_t i = 0; i < cpu.grey.size(); ++i) {
        inside += cpu.grey[i] > 0.0f;
        apart += std::abs(gpu.grey[i] - cpu.grey[i]) > 1.0f;
    }
    EXPECT_GT(double(inside), 0.95 * double(cpu.grey.size())) << "the plane lies in the volume";
    EXPECT_EQ(apart, 0u) << "pixels more than a grey level from the CPU twin's";
    EXPECT_EQ(ctx.validation_counter()->load(), 0u);
}

// A warped slice pipeline fetches slice_taps(map_step) map columns a run, from its first pixel's
// left one: every pixel of every run must find both its columns among them (a pixel that does not
// would take the run's first column's source), for images as fine as their map and far finer, of
// widths that leave a part run; and the live image reads no more than it needs.
TEST(EchoImageGpu, EveryPixelOfARunFindsItsMapColumnsAmongTheRunsTaps)
{
    using namespace kernels;
    for (const std::uint32_t columns : {7u, 100u, 333u, 400u, 401u, 512u, 1024u, 2048u})
        for (const std::uint32_t map_columns : {1u, 2u, 67u, 100u, 133u, 134u, 400u, 2048u}) {
            if (map_columns > columns) continue;
            SliceParams p{};
            p.map_columns = map_columns;
            p.map_step = float(double(map_columns) / double(columns));  // as echo::map_step makes it
            const uint taps = slice_taps(p.map_step);
            ASSERT_LE(taps, uint(SLICE_RUN) + 1u);
            for (uint run = 0; run < slice_runs(columns); ++run) {
                const uint c0 = run * uint(SLICE_RUN), first = map_tap(c0, p).left;
                for (uint j = 0; j < uint(SLICE_RUN); ++j) {
                    const MapTap t = map_tap(std::min(c0 + j, columns - 1), p);
                    ASSERT_GE(t.left, first);
                    ASSERT_LT(t.right - first, taps) << columns << " columns over " << map_columns << ", run " << run << ", pixel " << j;
                }
            }
        }
    EXPECT_EQ(slice_taps(float(134.0 / 1024.0)), 3u);  // the live 1024-column image over 0.3 mm labels
    EXPECT_EQ(slice_taps(1.0f), uint(SLICE_RUN) + 1u);
}

TEST(EchoImageGpu, RefusesVolumesItCannotRead)
{
    gpu::Context ctx(test::lavapipe_options());
    gpu::CommandPool pool(ctx);
    io::Volume grey = io::make_volume({8, 8, 8}, io::VoxelType::uint8);
    io::Volume wide = io::make_volume({8, 8, 8}, io::VoxelType::uint16);
    io::Volume shifted = grey;
    shifted.origin.x += 1;
    EXPECT_THROW(EchoVolumeGpu(pool, wide, nullptr), std::invalid_argument);
    EXPECT_THROW(EchoVolumeGpu(pool, grey, &wide), std::invalid_argument);
    EXPECT_THROW(EchoVolumeGpu(pool, grey, &shifted), std::invalid_argument);
}

}  // namespace
}  // namespace echosim::image

// The compute layer: 3-D images sampled through samplers, 2-D and 3-D dispatches, bindings of
// several kinds, and one descriptor set per frame slot. On lavapipe with validation on; the
// validation count is read after the device is gone, so leaks count.
#include "gpu/compute.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "echosim_test_kernels.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/kernels/pattern_bindings.h"
#include "gpu/kernels/pattern_expected.hpp"
#include "gpu/kernels/sample_volume_bindings.h"
#include "test_gpu.hpp"

namespace echosim::gpu {
namespace {

using test::kernels::PatternParams;
using test::kernels::SampleGrid;

// what the host reads after a dispatch must be written and visible first
void compute_to_host(VkCommandBuffer cmd)
{
    gpu::host_read_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

template <class T>
Buffer host_buffer(const Context& ctx, const T& value, VkBufferUsageFlags usage)
{
    Buffer b(ctx, sizeof(T), usage, MemoryUse::host_visible);
    b.write(std::as_bytes(std::span(&value, 1)));
    return b;
}

TEST(Groups, CoverEveryItemWithTheFewestGroups)
{
    const Groups a = Groups::cover(20u, 8u);
    EXPECT_EQ(a.x, 3u);
    EXPECT_EQ(a.y, 1u);
    const Groups b = Groups::cover(VkExtent2D{20, 13}, VkExtent2D{8, 8});
    EXPECT_EQ(b.x, 3u);
    EXPECT_EQ(b.y, 2u);
    EXPECT_EQ(b.z, 1u);
    const Groups c = Groups::cover(VkExtent3D{9, 7, 4}, VkExtent3D{4, 4, 4});
    EXPECT_EQ(c.x, 3u);
    EXPECT_EQ(c.y, 2u);
    EXPECT_EQ(c.z, 1u);
    EXPECT_EQ(Groups::cover(0u, 8u).x, 0u);
    EXPECT_EQ(Groups::cover(16u, 8u).x, 2u);
    EXPECT_THROW(Groups::cover(16u, 0u), std::invalid_argument);
}

TEST(Groups, CoverCountsUpToTheLargestItemCountWithoutWrapping)
{
    // items + group - 1 would wrap past UINT32_MAX here and give 0 groups
    EXPECT_EQ(Groups::cover(UINT32_MAX, 256u).x, 16777216u);  // (2^32 - 1) / 2^8, rounded up
    EXPECT_EQ(Groups::cover(UINT32_MAX, 1u).x, UINT32_MAX);
    EXPECT_EQ(Groups::cover(UINT32_MAX, UINT32_MAX).x, 1u);
    EXPECT_EQ(Groups::cover(UINT32_MAX - 1, UINT32_MAX).x, 1u);
    const Groups g = Groups::cover(VkExtent3D{UINT32_MAX, UINT32_MAX - 2, 5}, VkExtent3D{64, 3, 2});
    EXPECT_EQ(g.x, 67108864u);   // 2^26
    EXPECT_EQ(g.y, 1431655765u); // (2^32 - 3) / 3
    EXPECT_EQ(g.z, 3u);
}

TEST(Compute, AKernelWithNoBindingsIsDispatchedWithoutABind)
{
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        CommandPool pool(ctx);
        ComputeKernel kernel(ctx, test::kernels::push_only_comp, "push_only.comp", std::span<const BindingKind>(),
                             sizeof(std::uint32_t));
        const std::uint32_t value = 7;
        pool.submit_and_wait([&](VkCommandBuffer cmd) {
            for (int s = 0; s < kFramesInFlight; ++s)
                EXPECT_NO_THROW(kernel.record(cmd, s, std::as_bytes(std::span(&value, 1)), Groups::cover(3u, 1u)));
        });
        // binding nothing is still a bind of the right count; anything more is refused
        EXPECT_NO_THROW(kernel.bind(0, std::span<const Binding>()));
        Buffer b(ctx, 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::host_visible);
        EXPECT_THROW(kernel.bind(0, {Binding::storage(b)}), std::invalid_argument);
    }
    EXPECT_EQ(messages->load(), 0u);
}

// A small volume of random voxels; the expectations below read it as the sampler should.
struct Volume {
    std::uint32_t w = 5, h = 4, d = 3;
    std::vector<std::uint8_t> voxels;
    Volume()
    {
        std::mt19937 rng(11);
        voxels.resize(std::size_t(w) * h * d);
        for (auto& v : voxels) v = std::uint8_t(rng() % 256);
    }
    // the voxel at integer coordinates, clamped to the edge, as a UNORM value
    double at(int i, int j, int k) const
    {
        i = std::clamp(i, 0, int(w) - 1);
        j = std::clamp(j, 0, int(h) - 1);
        k = std::clamp(k, 0, int(d) - 1);
        return voxels[std::size_t(i) + w * (std::size_t(j) + h * std::size_t(k))] / 255.0;
    }
    // Vulkan's linear filter (texel centres at half-integers) with clamp to edge, written out
    double trilinear(glm::dvec3 p) const
    {
        const double u = p.x * w - 0.5, v = p.y * h - 0.5, s = p.z * d - 0.5;
        const int i = int(std::floor(u)), j = int(std::floor(v)), k = int(std::floor(s));
        const double a = u - i, b = v - j, c = s - k;
        double sum = 0;
        for (int dk = 0; dk < 2; ++dk)
            for (int dj = 0; dj < 2; ++dj)
                for (int di = 0; di < 2; ++di)
                    sum += (di ? a : 1 - a) * (dj ? b : 1 - b) * (dk ? c : 1 - c) * at(i + di, j + dj, k + dk);
        return sum;
    }
    double nearest(glm::dvec3 p) const
    {
        return at(int(std::floor(p.x * w)), int(std::floor(p.y * h)), int(std::floor(p.z * d)));
    }
};

TEST(Compute, SamplesA3dImageThroughLinearAndNearestSamplers)
{
    const Volume vol;
    // a 9x7x5 grid of points reaching past every face (clamp to edge), none of them on a texel
    // boundary, where nearest could go either way
    SampleGrid grid{};
    grid.origin = {-0.137f, -0.171f, -0.213f, 0};
    grid.step = {0.1597f, 0.2213f, 0.3311f, 0};
    grid.count = {9, 7, 5, 0};
    const std::size_t n = std::size_t(grid.count.x) * grid.count.y * grid.count.z;
    std::vector<glm::dvec3> points;
    for (std::uint32_t k = 0; k < grid.count.z; ++k)
        for (std::uint32_t j = 0; j < grid.count.y; ++j)
            for (std::uint32_t i = 0; i < grid.count.x; ++i) {
                const glm::vec3 p = glm::vec3(grid.origin) + glm::vec3(float(i), float(j), float(k)) * glm::vec3(grid.step);
                points.push_back(glm::dvec3(p));
                const glm::dvec3 t = glm::dvec3(p) * glm::dvec3(vol.w, vol.h, vol.d);
                for (int a = 0; a < 3; ++a) ASSERT_GT(std::abs(t[a] - std::round(t[a])), 1e-3) << "point on a texel boundary";
            }
    ASSERT_EQ(points.size(), n);

    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    std::vector<float> linear(n), nearest(n);
    std::uint32_t subtexel_bits = 0;
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        subtexel_bits = ctx.limits().subTexelPrecisionBits;
        CommandPool pool(ctx);
        Image volume(ctx, VkExtent3D{vol.w, vol.h, vol.d}, VK_FORMAT_R8_UNORM,
                     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        EXPECT_EQ(volume.type(), VK_IMAGE_TYPE_3D);
        upload_image(pool, volume, std::as_bytes(std::span(vol.voxels)));
        const Sampler linear_sampler(ctx, Filter::linear), nearest_sampler(ctx, Filter::nearest);
        const Buffer uniforms = host_buffer(ctx, grid, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        const Buffer out_linear(ctx, n * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::host_visible);
        const Buffer out_nearest(ctx, n * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::host_visible);

        static_assert(SAMPLE_VOLUME_VOLUME_BINDING == 0 && SAMPLE_VOLUME_GRID_BINDING == 1 && SAMPLE_VOLUME_OUT_BINDING == 2);
        ComputeKernel kernel(ctx, test::kernels::sample_volume_comp, "sample_volume.comp",
                             {BindingKind::sampled_image, BindingKind::uniform_buffer, BindingKind::storage_buffer}, 0);
        // the two frame slots sample the same volume through different samplers into different buffers
        kernel.bind(0, {Binding::sampled(volume, linear_sampler), Binding::uniform(uniforms), Binding::storage(out_linear)});
        kernel.bind(1, {Binding::sampled(volume, nearest_sampler), Binding::uniform(uniforms), Binding::storage(out_nearest)});
        const Groups groups = Groups::cover(VkExtent3D{grid.count.x, grid.count.y, grid.count.z},
                                            VkExtent3D{SAMPLE_VOLUME_GROUP_SIZE, SAMPLE_VOLUME_GROUP_SIZE, SAMPLE_VOLUME_GROUP_SIZE});
        EXPECT_GT(groups.z, 1u);  // a real 3-D dispatch
        pool.submit_and_wait([&](VkCommandBuffer cmd) {
            kernel.record(cmd, 0, {}, groups);
            kernel.record(cmd, 1, {}, groups);
            compute_to_host(cmd);
        });
        std::memcpy(linear.data(), out_linear.mapped(), n * sizeof(float));
        std::memcpy(nearest.data(), out_nearest.mapped(), n * sizeof(float));
    }
    EXPECT_EQ(messages->load(), 0u);

    // the filter weights are fixed point with subTexelPrecisionBits fraction bits (at least 4 by
    // the specification, 8 on lavapipe): each of the three weights may be off by one step, on a
    // value range of at most 1, and the result may be rounded to 8 bits
    const double tolerance = 3.0 * std::ldexp(1.0, -int(subtexel_bits)) + 1.0 / 255.0;
    ASSERT_LT(tolerance, 0.05) << "too coarse a filter to test against";
    double worst = 0;
    int filtered = 0;  // points where linear and nearest really differ
    for (std::size_t i = 0; i < n; ++i) {
        const double expected = vol.trilinear(points[i]);
        worst = std::max(worst, std::abs(linear[i] - expected));
        EXPECT_NEAR(linear[i], expected, tolerance) << "point " << i;
        EXPECT_FLOAT_EQ(nearest[i], float(vol.nearest(points[i]))) << "point " << i;
        filtered += std::abs(expected - vol.nearest(points[i])) > 4 * tolerance;
    }
    EXPECT_GT(filtered, int(n) / 2) << "the points do not tell linear from nearest";
    std::printf("linear sampling: worst difference from the CPU trilinear %.5f (tolerance %.5f, %u sub-texel bits)\n", worst,
                tolerance, subtexel_bits);
}

// The pattern kernel into one storage image per frame slot, each slot with its own uniforms.
TEST(Compute, TwoDimensionalDispatchesWriteEachSlotsOwnStorageImage)
{
    const VkExtent2D sizes[kFramesInFlight] = {{20, 13}, {9, 17}};
    const std::uint32_t seeds[kFramesInFlight] = {3, 200};
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    std::vector<std::byte> texels[kFramesInFlight];
    {
        Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        CommandPool pool(ctx);
        static_assert(PATTERN_IMAGE_BINDING == 0 && PATTERN_PARAMS_BINDING == 1);
        ComputeKernel kernel(ctx, test::kernels::pattern_comp, "pattern.comp",
                             {BindingKind::storage_image, BindingKind::uniform_buffer}, 0);
        std::vector<Image> images;
        std::vector<Buffer> params;
        for (int s = 0; s < kFramesInFlight; ++s) {
            images.emplace_back(ctx, sizes[s], VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                VK_IMAGE_ASPECT_COLOR_BIT);
            params.push_back(host_buffer(ctx, PatternParams{seeds[s], sizes[s].width, sizes[s].height, 0}, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        }
        // a binding of the wrong kind is refused when bound, not found by the GPU
        EXPECT_THROW(kernel.bind(0, {Binding::storage(params[0]), Binding::uniform(params[0])}), std::invalid_argument);
        EXPECT_THROW(kernel.bind(kFramesInFlight, {Binding::storage(images[0]), Binding::uniform(params[0])}), std::out_of_range);
        for (int s = 0; s < kFramesInFlight; ++s) kernel.bind(s, {Binding::storage(images[std::size_t(s)]), Binding::uniform(params[std::size_t(s)])});

        pool.submit_and_wait([&](VkCommandBuffer cmd) {
            for (int s = kFramesInFlight - 1; s >= 0; --s) {
                transition(cmd, images[std::size_t(s)].handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
                kernel.record(cmd, s, {}, Groups::cover(sizes[s], VkExtent2D{PATTERN_GROUP_X, PATTERN_GROUP_Y}));
            }
        });
        for (int s = 0; s < kFramesInFlight; ++s) texels[s] = download_image(pool, images[std::size_t(s)], VK_IMAGE_LAYOUT_GENERAL);
    }
    EXPECT_EQ(messages->load(), 0u);

    for (int s = 0; s < kFramesInFlight; ++s) {
        ASSERT_EQ(texels[s].size(), std::size_t(sizes[s].width) * sizes[s].height * 4);
        int wrong = 0;
        for (std::uint32_t y = 0; y < sizes[s].height; ++y)
            for (std::uint32_t x = 0; x < sizes[s].width; ++x) {
                const auto want = test::pattern_texel(x, y, seeds[s]);
                const std::byte* got = &texels[s][(std::size_t(y) * sizes[s].width + x) * 4];
                wrong += std::memcmp(got, want.data(), 4) != 0;
            }
        EXPECT_EQ(wrong, 0) << "slot " << s << ": texels unlike pattern(seed " << seeds[s] << ")";
    }
}

}  // namespace
}  // namespace echosim::gpu

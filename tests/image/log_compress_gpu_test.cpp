// The GPU kernel of log compression (engine/image) against its CPU reference (engine/echo), on
// lavapipe with validation on; the validation count is read after the device is gone.
#include "image/log_compress_gpu.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "echo/log_compress.hpp"
#include "test_gpu.hpp"

namespace echosim::image {
namespace {

using echo::log_compress_cpu;
using echo::LogCompressParams;

std::uint32_t grey(std::uint32_t rgba) { return rgba & 0xffu; }

TEST(LogCompress, GpuKernelMatchesCpuReference)
{
    // Rayleigh-distributed envelope over 80 dB, like speckle
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(1e-6f, 1.0f);
    std::vector<float> envelope(300'001);
    for (float& e : envelope) e = 50.0f * std::sqrt(-2.0f * std::log(u(rng))) * std::pow(10.0f, -4.0f * u(rng));
    const LogCompressParams p{0, 120.0f, 3.0f, 55.0f};
    const auto cpu = log_compress_cpu(envelope, p);

    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    std::vector<std::uint32_t> gpu;
    {
        gpu::Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        gpu::CommandPool pool(ctx);
        image::LogCompressGpu kernel(ctx, std::uint32_t(envelope.size()));
        gpu = kernel.run(pool, envelope, p);
    }
    EXPECT_EQ(messages->load(), 0u);
    ASSERT_EQ(gpu.size(), cpu.size());
    // tolerance: one grey level (log10 in C++ vs log2 * log10(2) on the GPU round differently at
    // level boundaries), and at most 0.5 % of pixels off by that one level
    std::size_t off = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        const int d = int(grey(gpu[i])) - int(grey(cpu[i]));
        ASSERT_LE(std::abs(d), 1) << "pixel " << i << " envelope " << envelope[i];
        off += d != 0;
        ASSERT_EQ(gpu[i] >> 8 & 0xffffu, grey(gpu[i]) * 0x101u) << "pixel " << i << " is not grey";
    }
    EXPECT_LE(double(off) / double(cpu.size()), 0.005);
}

}  // namespace
}  // namespace echosim::image

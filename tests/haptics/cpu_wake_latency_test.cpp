// The haptic loop's wake-latency request (engine/haptics/cpu_wake_latency.hpp) against a plain file
// standing in for /dev/cpu_dma_latency: the bound is written as the kernel reads it (one binary
// 32-bit integer), a refusal names the file and the reason, and the request goes when released.
#include "haptics/cpu_wake_latency.hpp"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace echosim::haptics {
namespace {

// an empty file: the device exists before the request opens it
std::filesystem::path stand_in(const char* name)
{
    const std::filesystem::path p = test::temp_path("wake", name);
    test::write_bytes(p, "");
    return p;
}

TEST(CpuWakeLatency, WritesTheBoundAsOneBinaryInt32)
{
    for (std::int32_t bound : {0, 25, 70000}) {
        const auto file = stand_in("wake_bound");
        {
            CpuWakeLatency request(bound, file.string());
            EXPECT_TRUE(request.held()) << request.refusal();
            EXPECT_EQ(request.refusal(), "");
        }
        const std::string b = test::read_bytes(file);
        ASSERT_EQ(b.size(), 4u) << "bound " << bound;
        std::int32_t written = -1;
        std::memcpy(&written, b.data(), 4);
        EXPECT_EQ(written, bound);
        std::filesystem::remove(file);
    }
}

TEST(CpuWakeLatency, ARefusalNamesTheFileAndWhy)
{
    const std::string missing = (test::temp_path("wake", "no_such_dir") / "cpu_dma_latency").string();
    CpuWakeLatency request(0, missing);
    EXPECT_FALSE(request.held());
    EXPECT_NE(request.refusal().find(missing), std::string::npos) << request.refusal();
    EXPECT_NE(request.refusal().find("No such file"), std::string::npos) << request.refusal();
    EXPECT_EQ(request.refusal().find("udev"), std::string::npos) << "a permission hint for a missing file: " << request.refusal();

    const auto file = stand_in("wake_negative");
    CpuWakeLatency negative(-1, file.string());
    EXPECT_FALSE(negative.held());
    EXPECT_NE(negative.refusal().find("-1 us"), std::string::npos) << negative.refusal();
    EXPECT_TRUE(test::read_bytes(file).empty()) << "a refused bound was written";
    std::filesystem::remove(file);
}

TEST(CpuWakeLatency, ReleasedOnceWhenMovedOrReleased)
{
    const auto file = stand_in("wake_move");
    CpuWakeLatency a(0, file.string());
    ASSERT_TRUE(a.held());
    CpuWakeLatency b = std::move(a);
    EXPECT_FALSE(a.held());  // NOLINT(bugprone-use-after-move): the moved-from request holds nothing
    EXPECT_TRUE(b.held());
    CpuWakeLatency c;
    EXPECT_FALSE(c.held());
    EXPECT_EQ(c.refusal(), "");
    c = std::move(b);
    EXPECT_TRUE(c.held());
    c.release();
    EXPECT_FALSE(c.held());
    c.release();  // twice is harmless
    EXPECT_EQ(test::read_bytes(file).size(), 4u);  // written once, by the one request
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace echosim::haptics

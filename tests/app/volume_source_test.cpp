#include "app/volume_source.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "io/volume_file.hpp"
#include "test_files.hpp"

namespace echosim::app {
namespace {

std::filesystem::path temp(const std::string& name) { return test::temp_path("volume_source_test", name); }

io::Volume ramp(io::VoxelType type)
{
    io::Volume v = io::make_volume({4, 2, 2}, type);
    v.origin = {1, 2, 3};
    for (std::size_t i = 0; i < v.voxel_count(); ++i) {
        if (type == io::VoxelType::uint16) v.as<std::uint16_t>()[i] = std::uint16_t(1000 + 200 * i);  // 1000..4000
        if (type == io::VoxelType::int16) v.as<std::int16_t>()[i] = std::int16_t(int(i) % 4);         // codes 0..3
        if (type == io::VoxelType::float32) v.as<float>()[i] = -1.0f + 0.5f * float(i);                  // -1..6.5
    }
    return v;
}

TEST(VolumeSource, MapsAWideVolumeOntoGreyFromItsMinToItsMax)
{
    const auto volume = temp("wide.mha"), labels = temp("labels.mha");
    io::write_volume(volume, ramp(io::VoxelType::uint16), true);
    io::write_volume(labels, ramp(io::VoxelType::int16), false);  // Slicer writes label maps as short
    const VolumePair pair = user_volume(volume, labels);
    ASSERT_EQ(pair.volume->type, io::VoxelType::uint8);
    const std::uint8_t* grey = pair.volume->as<std::uint8_t>();
    EXPECT_EQ(grey[0], 0);      // 1000, the minimum
    EXPECT_EQ(grey[15], 255);   // 4000, the maximum
    EXPECT_EQ(grey[5], 85);     // 2000: a third of the way
    EXPECT_EQ(pair.volume->origin, glm::dvec3(1, 2, 3));
    EXPECT_NE(pair.description.find("unsigned short voxels 1000..4000 mapped linearly onto grey 0..255"), std::string::npos)
        << pair.description;
    ASSERT_EQ(pair.labels->type, io::VoxelType::uint8);
    EXPECT_EQ(pair.labels->as<std::uint8_t>()[7], 3);

    io::write_volume(volume, ramp(io::VoxelType::float32), false);
    const VolumePair floats = user_volume(volume, {});
    EXPECT_EQ(floats.volume->as<std::uint8_t>()[2], 34);  // 0 of -1..6.5: 255 * 1 / 7.5 = 34
    EXPECT_NE(floats.description.find("float voxels -1..6.5"), std::string::npos) << floats.description;
    std::filesystem::remove(volume);
    std::filesystem::remove(labels);
}

TEST(VolumeSource, RefusesLabelsThatAreNotTissueCodes)
{
    const auto volume = temp("grey.nrrd"), labels = temp("bad_labels.mha");
    io::write_volume(volume, io::make_volume({4, 2, 2}, io::VoxelType::uint8), false);
    io::Volume l = ramp(io::VoxelType::float32);
    io::write_volume(labels, l, false);
    try {
        user_volume(volume, labels);
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(labels.string()), std::string::npos) << message;
        EXPECT_NE(message.find("voxel (0, 0, 0) is -1, not a tissue code"), std::string::npos) << message;
    }
    std::filesystem::remove(volume);
    std::filesystem::remove(labels);
}

// What `write` writes to a stream, as text.
std::string written(const std::function<void(std::FILE*)>& write)
{
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* out = open_memstream(&buffer, &size);
    write(out);
    std::fclose(out);
    std::string text(buffer, size);
    std::free(buffer);
    return text;
}

// The progress of the default volume's making, as a terminal and as a log receive it.
std::string progress_text(bool terminal)
{
    return written([terminal](std::FILE* out) {
        TerminalProgress progress("echosim x", out, terminal);
        const std::function<void(const std::string&, double)> copy = progress;  // as case_volume keeps it
        for (int i = 0; i <= 200; ++i) copy("imaging", i / 200.0);
        for (int i = 0; i <= 10; ++i) copy("filling", i / 10.0);
        progress.finish();
        progress.finish();  // a second finish adds nothing
    });
}

TEST(TerminalProgress, OnATerminalOneLineRewrittenInPlaceAndEnded)
{
    const std::string t = progress_text(true);
    // one update a whole percent, each back to the line's start and clearing what it leaves
    EXPECT_EQ(std::count(t.begin(), t.end(), '\r'), 101 + 11);
    EXPECT_NE(t.find("\rechosim x: making the default volume (once; it is cached): imaging  50 %\033[K"), std::string::npos) << t;
    EXPECT_EQ(std::count(t.begin(), t.end(), '\n'), 1);  // ended once, by finish()
    EXPECT_TRUE(t.ends_with("filling 100 %\033[K\n")) << t;
}

TEST(TerminalProgress, InALogWholeLinesAtEachQuarter)
{
    const std::string t = progress_text(false);
    EXPECT_EQ(t.find('\r'), std::string::npos);
    EXPECT_EQ(t.find('\033'), std::string::npos);
    std::string expected;
    for (const char* stage : {"imaging", "filling"})
        for (int q = 0; q <= 100; q += 25)
            expected += std::string("echosim x: making the default volume (once; it is cached): ") + stage + " " + (q < 10 ? "  " : q < 100 ? " " : "") +
                        std::to_string(q) + " %\n";
    EXPECT_EQ(t, expected);
}

TEST(TerminalProgress, NothingShownNothingEnded)
{
    // a cached volume: no progress was called
    EXPECT_EQ(written([](std::FILE* out) { TerminalProgress("echosim x", out, true).finish(); }), "");
}

}  // namespace
}  // namespace echosim::app

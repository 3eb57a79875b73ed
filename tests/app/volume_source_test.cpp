#include "app/volume_source.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "io/owned_temp.hpp"
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

// A run killed while it made the default volume left its half-written folder in the cache; the next
// run removes it (and only it: not one that a live run is writing, nor anything else there).
TEST(VolumeSource, RemovesTheHalfWrittenCacheOfARunThatIsGone)
{
    const auto cache = temp("cache");
    std::filesystem::remove_all(cache);
    const char* old_xdg = std::getenv("XDG_CACHE_HOME");
    const std::string saved = old_xdg ? old_xdg : "";
    ::setenv("XDG_CACHE_HOME", cache.c_str(), 1);

    // a cached pair, so that no volume is made here
    const auto folder = case_volume_folder(echo::Case::healthy);
    std::filesystem::create_directories(folder);
    io::write_volume(folder / "volume.nrrd", io::make_volume({4, 2, 2}, io::VoxelType::uint8), false);
    io::write_volume(folder / "labels.nrrd", io::make_volume({4, 2, 2}, io::VoxelType::uint8), false);
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // its PID names no process now
    const auto killed = folder.parent_path() / (folder.filename().string() + ".echosim-partial-" + std::to_string(child) + "-abc123");
    std::filesystem::create_directories(killed);
    io::write_volume(killed / "volume.nrrd", io::make_volume({4, 2, 2}, io::VoxelType::uint8), false);
    const io::OwnedTemp live = io::create_owned_folder(folder.parent_path(), "other-0.3mm-v1", ".echosim-partial-");
    const auto unrelated = folder.parent_path() / "notes.partial";
    test::write_bytes(unrelated, "mine");

    const VolumePair pair = case_volume(echo::Case::healthy, {});
    EXPECT_NE(pair.description.find("cached in"), std::string::npos) << pair.description;
    EXPECT_FALSE(std::filesystem::exists(killed));
    EXPECT_TRUE(std::filesystem::is_directory(live.path));
    EXPECT_EQ(test::read_bytes(unrelated), "mine");

    ::close(live.fd);
    if (old_xdg) ::setenv("XDG_CACHE_HOME", saved.c_str(), 1);
    else ::unsetenv("XDG_CACHE_HOME");
    std::filesystem::remove_all(cache);
}

}  // namespace
}  // namespace echosim::app

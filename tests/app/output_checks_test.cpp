// The checks every writing command makes before its work (engine/app/output_checks.cpp), and the
// writing of files that belong together.
#include <climits>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "app/commands.hpp"
#include "io/owned_temp.hpp"
#include "io/partial_file.hpp"
#include "test_files.hpp"

namespace echosim::app {
namespace {

std::filesystem::path fresh_folder(const std::string& name)
{
    const auto folder = test::temp_path("output_checks", name);
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

std::set<std::string> names_in(const std::filesystem::path& folder)
{
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(folder)) names.insert(e.path().filename().string());
    return names;
}

// Outputs are compared by what they name: another spelling of the same place, a link to an input or
// a hard link to it are the same file; a neighbour is not.
TEST(OutputChecks, TellsTheSameFileHoweverItIsSpelt)
{
    const auto folder = fresh_folder("same");
    std::filesystem::create_directories(folder / "sub");
    const auto input = folder / "sweep.mha";
    test::write_bytes(input, "input");
    std::filesystem::create_symlink(input, folder / "link.mha");
    std::filesystem::create_hard_link(input, folder / "hard.mha");

    EXPECT_FALSE(outputs_distinct("test", {{"--out", folder / "sub" / ".." / "sweep.mha"}}, {{"--sweep", input}}));
    EXPECT_FALSE(outputs_distinct("test", {{"--out", folder / "link.mha"}}, {{"--sweep", input}}));
    EXPECT_FALSE(outputs_distinct("test", {{"--out", folder / "hard.mha"}}, {{"--sweep", input}}));
    // two outputs, neither there yet
    EXPECT_FALSE(outputs_distinct("test", {{"--out", folder / "p.nrrd"}, {"--labels", folder / "." / "p.nrrd"}}, {}));
    EXPECT_TRUE(outputs_distinct("test", {{"--out", folder / "p.nrrd"}, {"--labels", folder / "q.nrrd"}, {"--map", ""}},
                                 {{"--sweep", input}, {"--config", ""}}));
    std::filesystem::remove_all(folder);
}

// A name the file system takes is accepted, one byte more is refused before the work, and so is a
// path that would be too long once the staging folder and the temporary's suffix are added.
TEST(OutputChecks, RefusesNamesTooLongToWrite)
{
    const auto folder = fresh_folder("long");
    EXPECT_TRUE(output_path_usable("test", "--out", folder / std::string(NAME_MAX, 'n')));
    EXPECT_FALSE(output_path_usable("test", "--out's labels", folder / std::string(NAME_MAX + 1, 'n')));
    // folders nested until the path is a few bytes short of PATH_MAX: the file itself would fit
    std::filesystem::path deep = folder;
    while (deep.string().size() + 200 < PATH_MAX - 60) deep /= std::string(199, 'd');
    std::filesystem::create_directories(deep);
    const std::filesystem::path out = deep / std::string(PATH_MAX - 10 - deep.string().size(), 'f');
    ASSERT_LT(out.string().size(), std::size_t(PATH_MAX));
    EXPECT_FALSE(output_path_usable("test", "--out", out));
    std::filesystem::remove_all(folder);
}

// A run killed while writing a set left its staging folder; the next write there removes it, but
// not one a live run is writing in, and it leaves nothing of its own.
TEST(OutputChecks, WriteTogetherRemovesTheStagingOfARunThatIsGone)
{
    const auto folder = fresh_folder("together");
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // its PID names no process now
    const std::string killed = ".echosim-writing-" + std::to_string(child) + "-abc123";
    std::filesystem::create_directories(folder / killed);
    test::write_bytes(folder / killed / "v.nrrd", "half");
    const io::OwnedTemp live = io::create_owned_folder(folder, "", ".echosim-writing-");

    write_together({folder / "v.nrrd", folder / "v.labels.nrrd"}, [](std::size_t i, const std::filesystem::path& path) {
        io::write_file<std::runtime_error>(path, i == 0 ? "volume" : "labels");
    });
    EXPECT_EQ(names_in(folder), (std::set<std::string>{"v.nrrd", "v.labels.nrrd", live.path.filename().string()}));
    EXPECT_EQ(test::read_bytes(folder / "v.labels.nrrd"), "labels");

    // a failure midway: the old files stay, and nothing is left behind
    EXPECT_THROW(write_together({folder / "v.nrrd", folder / "v.labels.nrrd"},
                                [](std::size_t i, const std::filesystem::path& path) {
                                    if (i == 1) throw std::runtime_error("disk full");
                                    io::write_file<std::runtime_error>(path, "new");
                                }),
                 std::runtime_error);
    EXPECT_EQ(names_in(folder), (std::set<std::string>{"v.nrrd", "v.labels.nrrd", live.path.filename().string()}));
    EXPECT_EQ(test::read_bytes(folder / "v.nrrd"), "volume");
    ::close(live.fd);
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace echosim::app

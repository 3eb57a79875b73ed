#include "io/partial_file.hpp"

#include <climits>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace echosim::io {
namespace {

// An output named over something that is not a regular file is refused, and the thing stays what
// it was (here a FIFO and a folder; a device node such as /dev/null would be replaced the same way,
// and is not risked in a test that runs as root in CI).
TEST(PartialFile, RefusesToReplaceWhatIsNotARegularFile)
{
    const auto fifo = test::temp_path("partial", "fifo");
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto folder = test::temp_path("partial", "folder");
    std::filesystem::create_directories(folder);
    for (const auto& path : {fifo, folder}) {
        try {
            PartialFile<std::runtime_error> out(path);
            out.write("data");
            out.commit();
            ADD_FAILURE() << "wrote over " << path;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        }
        for (const auto& e : std::filesystem::directory_iterator(path.parent_path()))
            EXPECT_EQ(e.path().filename().string().find(path.filename().string() + kPartialMarker), std::string::npos) << e.path();
    }
    EXPECT_TRUE(std::filesystem::is_fifo(fifo));
    EXPECT_TRUE(std::filesystem::is_directory(folder));
    std::filesystem::remove(fifo);
    std::filesystem::remove(folder);

    // a regular file is replaced whole, as always
    const auto file = test::temp_path("partial", "file");
    test::write_bytes(file, "old");
    PartialFile<std::runtime_error> out(file);
    out.write("new");
    out.commit();
    EXPECT_EQ(test::read_bytes(file), "new");
    std::filesystem::remove(file);
}

// The names in a folder, for checking that a writer left nothing else behind.
std::set<std::string> names_in(const std::filesystem::path& folder)
{
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(folder)) names.insert(e.path().filename().string());
    return names;
}

std::filesystem::path fresh_folder(const std::string& name)
{
    const auto folder = test::temp_path("partial", name);
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

// A link planted under the name the temporary once had (FILE.partial) is neither written through
// nor removed, whether the write completes or fails; the output is a file of its own.
TEST(PartialFile, NeverWritesThroughAPlantedLink)
{
    const auto folder = fresh_folder("planted");
    const auto victim = folder / "victim.txt", out = folder / "out.txt", link = folder / "out.txt.partial";
    test::write_bytes(victim, "secret");
    std::filesystem::create_symlink(victim, link);
    {
        PartialFile<std::runtime_error> failed(out);
        failed.write("half");
    }  // never committed
    {
        PartialFile<std::runtime_error> done(out);
        done.write("new");
        done.commit();
    }
    EXPECT_EQ(test::read_bytes(victim), "secret");
    EXPECT_TRUE(std::filesystem::is_symlink(link));
    EXPECT_FALSE(std::filesystem::is_symlink(out));
    EXPECT_EQ(test::read_bytes(out), "new");
    EXPECT_EQ(names_in(folder), (std::set<std::string>{"victim.txt", "out.txt", "out.txt.partial"}));
    std::filesystem::remove_all(folder);
}

// A name as long as the folder allows is written: the temporary's own name is cut short to fit
// (once, FILE.partial was one name too long, and the write failed after all the work).
TEST(PartialFile, WritesANameAsLongAsTheFolderAllows)
{
    const auto folder = fresh_folder("long");
    const std::string name(NAME_MAX, 'n');
    PartialFile<std::runtime_error> out(folder / name);
    out.write("long");
    out.commit();
    EXPECT_EQ(test::read_bytes(folder / name), "long");
    EXPECT_EQ(names_in(folder), std::set<std::string>{name});
    std::filesystem::remove_all(folder);
}

// A process killed while writing leaves its temporary; the next write of the same file removes it,
// and nothing else: not another file's, not a link, not one a live writer holds.
TEST(PartialFile, RemovesTheTemporariesOfWritersThatAreGone)
{
    const auto folder = fresh_folder("stale");
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_GT(child, 0);
    ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // gone: its PID names no process now
    const std::string dead = std::to_string(child);
    const std::string ours = std::string(kPartialMarker) + dead;
    test::write_bytes(folder / ("out.txt" + ours + "-abc123"), "killed midway");
    test::write_bytes(folder / ("other.txt" + ours + "-abc123"), "another file's");
    std::filesystem::create_symlink(folder / "other.txt", folder / ("out.txt" + ours + "-link00"));
    std::filesystem::create_directories(folder / ("out.txt" + ours + "-drafts"));  // a folder: not what a PartialFile makes
    test::write_bytes(folder / ("out.txt.partial-" + dead + "-abc123"), "a user's, of a name like ours");
    const OwnedTemp live = create_owned_file(folder, "out.txt", kPartialMarker);  // a writer at work
    PartialFile<std::runtime_error> out(folder / "out.txt");
    out.write("new");
    out.commit();
    EXPECT_EQ(names_in(folder), (std::set<std::string>{"out.txt", "other.txt" + ours + "-abc123", "out.txt" + ours + "-link00",
                                                       "out.txt" + ours + "-drafts", "out.txt.partial-" + dead + "-abc123",
                                                       live.path.filename().string()}));
    ::close(live.fd);
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace echosim::io

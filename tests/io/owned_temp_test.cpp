#include "io/owned_temp.hpp"

#include <chrono>
#include <filesystem>
#include <string>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace echosim::io {
namespace {

std::filesystem::path fresh_folder(const std::string& name)
{
    const auto folder = test::temp_path("owned_temp", name);
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

// A PID that names no process: a child that has exited and been reaped.
pid_t dead_pid()
{
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    EXPECT_GT(child, 0);
    EXPECT_EQ(::waitpid(child, nullptr, 0), child);
    return child;
}

void make_old(const std::filesystem::path& path)
{
    std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now() - kStaleAge - std::chrono::minutes(1));
}

TEST(OwnedTemp, NamesAreUniqueExclusiveAndParsedBack)
{
    const auto folder = fresh_folder("names");
    const OwnedTemp a = create_owned_file(folder, "v.nrrd", ".partial-");
    const OwnedTemp b = create_owned_file(folder, "v.nrrd", ".partial-");
    EXPECT_NE(a.path, b.path);
    const std::string name = a.path.filename().string();
    EXPECT_EQ(name.rfind("v.nrrd.partial-" + std::to_string(::getpid()) + "-", 0), 0u) << name;
    EXPECT_EQ(owned_head(name, ".partial-"), std::optional<std::string>("v.nrrd"));
    EXPECT_EQ(owned_head("v.nrrd.partial", ".partial-"), std::nullopt);
    EXPECT_EQ(owned_head("v.nrrd.partial-12x-abcdef", ".partial-"), std::nullopt);
    const OwnedTemp d = create_owned_folder(folder, "", ".echosim-writing-");
    EXPECT_TRUE(std::filesystem::is_directory(d.path));
    EXPECT_EQ(owned_head(d.path.filename().string(), ".echosim-writing-"), std::optional<std::string>(""));
    for (const OwnedTemp& t : {a, b, d}) ::close(t.fd);
    std::filesystem::remove_all(folder);
}

// Who may remove a temporary: never while its owner holds the lock (however old it is), nor while
// its PID is alive and it is new (the moment between making and locking it); once the lock is free,
// when the PID is gone or the temporary is old (the PID reused).
TEST(OwnedTemp, RemovesOnlyTemporariesWhoseOwnerIsGone)
{
    const auto folder = fresh_folder("stale");
    const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getpid());
    const OwnedTemp held = create_owned_folder(folder, "", ".w-");
    make_old(held.path);
    std::filesystem::create_directories(folder / (".w-" + dead + "-000000") / "inside");  // killed while writing
    test::write_bytes(folder / (".w-" + alive + "-111111"), "");                        // new, not locked yet
    test::write_bytes(folder / (".w-" + alive + "-222222"), "");                        // old: the PID reused
    make_old(folder / (".w-" + alive + "-222222"));
    std::filesystem::create_symlink(folder / "elsewhere", folder / (".w-" + dead + "-333333"));  // a link: never
    ::mkfifo((folder / (".w-" + dead + "-444444")).c_str(), 0600);                               // not a file: never
    test::write_bytes(folder / ("x.w-" + dead + "-555555"), "");  // another head: kept when a head is asked for
    std::filesystem::create_directories(folder / (".w-" + dead + "-2024-drafts"));  // a name of the shape, not ours: never

    EXPECT_EQ(remove_stale(folder, ".w-", ""), 2u);  // the empty head only
    EXPECT_TRUE(std::filesystem::exists(held.path));
    EXPECT_FALSE(std::filesystem::exists(folder / (".w-" + dead + "-000000")));
    EXPECT_TRUE(std::filesystem::exists(folder / (".w-" + alive + "-111111")));
    EXPECT_FALSE(std::filesystem::exists(folder / (".w-" + alive + "-222222")));
    EXPECT_TRUE(std::filesystem::is_symlink(folder / (".w-" + dead + "-333333")));
    EXPECT_TRUE(std::filesystem::is_fifo(folder / (".w-" + dead + "-444444")));
    EXPECT_TRUE(std::filesystem::exists(folder / ("x.w-" + dead + "-555555")));
    EXPECT_TRUE(std::filesystem::exists(folder / (".w-" + dead + "-2024-drafts")));

    test::write_bytes(folder / ("y.w-" + dead + "-555555"), "");
    EXPECT_EQ(remove_stale(folder, ".w-", std::string("y")), 1u);
    EXPECT_TRUE(std::filesystem::exists(folder / ("x.w-" + dead + "-555555")));

    // a sweep for folders leaves files of the same name alone, and one for files folders
    ::close(held.fd);  // its owner is done with it: old and unlocked, it is stale now
    EXPECT_EQ(remove_stale(folder, ".w-", std::nullopt, TempKind::files), 1u);  // x.w-: any head
    EXPECT_TRUE(std::filesystem::exists(held.path));
    EXPECT_EQ(remove_stale(folder, ".w-", std::nullopt, TempKind::folders), 1u);
    EXPECT_FALSE(std::filesystem::exists(held.path));
    EXPECT_TRUE(std::filesystem::exists(folder / (".w-" + dead + "-2024-drafts")));
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace echosim::io

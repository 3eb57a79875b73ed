#include "io/partial_file.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

#include <sys/stat.h>

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
        EXPECT_FALSE(std::filesystem::exists(path.string() + ".partial"));
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

}  // namespace
}  // namespace echosim::io

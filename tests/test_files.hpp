// Scratch files for tests: unique names in the temporary folder, whole-file reads and writes, a
// one-place text edit for making broken variants of a good file, and the check that a reader's
// error names the file and what is wrong with it.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

namespace echosim::test {

inline std::filesystem::path temp_path(const std::string& prefix, const std::string& name)
{
    return std::filesystem::temp_directory_path() / ("echosim_" + prefix + "_" + std::to_string(::getpid()) + "_" + name);
}

inline std::string read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
}

// `text` with its one occurrence of `from` replaced by `to` (a failed expectation if absent).
inline std::string with(std::string text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the test text";
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// read() must throw an Error whose message names `path` and holds every one of `words`.
template <class Error, class Read>
void expect_error_naming(const std::filesystem::path& path, std::initializer_list<const char*> words, Read&& read)
{
    try {
        read();
        ADD_FAILURE() << "no error reading " << path;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        for (const char* word : words) EXPECT_NE(message.find(word), std::string::npos) << "no '" << word << "' in: " << message;
    }
}

// read(path) must refuse, with an Error naming the path and "not a regular file", each of: a FIFO
// (reading would block until a writer came), a folder, and /dev/zero (reading would never end; it is
// only read from, never written, so safe in a test that runs as root).
template <class Error, class Read>
void expect_special_files_refused(const std::string& prefix, Read&& read)
{
    const auto fifo = temp_path(prefix, "fifo");
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto folder = temp_path(prefix, "folder");
    std::filesystem::create_directories(folder);
    for (const std::filesystem::path& path : {fifo, folder, std::filesystem::path("/dev/zero")})
        expect_error_naming<Error>(path, {"not a regular file"}, [&] { read(path); });
    std::filesystem::remove(fifo);
    std::filesystem::remove(folder);
}

}  // namespace echosim::test

// Scratch files for tests: unique names in the temporary folder, whole-file reads and writes, and
// a one-place text edit for making broken variants of a good file.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
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

}  // namespace echosim::test

#include "input_file.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace echosim::fuzz {
namespace {

std::filesystem::path make_private_folder()
{
    std::error_code ec;
    const bool shm = std::filesystem::is_directory("/dev/shm", ec);  // memory: no disk I/O per input
    const std::filesystem::path base = shm ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    std::string pattern = (base / "echosim_fuzz_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("fuzz: cannot make a folder under " + base.string());
    return pattern;
}

// made on first use, never destroyed (the exit handler removing the folder still needs its name)
const std::filesystem::path& private_folder()
{
    static const std::filesystem::path* const folder = [] {
        const auto* f = new std::filesystem::path(make_private_folder());
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(private_folder(), ec);
        });
        return f;
    }();
    return *folder;
}

}  // namespace

std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, std::string_view name)
{
    std::filesystem::path path = private_folder() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) throw std::runtime_error("fuzz: cannot write " + path.string());
    return path;
}

}  // namespace echosim::fuzz

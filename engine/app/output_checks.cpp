#include <cstdio>
#include <filesystem>
#include <system_error>

#include "app/commands.hpp"

namespace echosim::app {

bool output_path_usable(const char* command, const char* option, const std::filesystem::path& path)
{
    const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(parent)) {
        std::fprintf(stderr, "echosim %s: %s %s: folder %s does not exist\n", command, option, path.c_str(), parent.c_str());
        return false;
    }
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
        std::fprintf(stderr, "echosim %s: %s %s: not a regular file (a device, a FIFO or a folder); refusing to replace it\n",
                     command, option, path.c_str());
        return false;
    }
    return true;
}

}  // namespace echosim::app

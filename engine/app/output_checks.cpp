#include <cstdio>

#include "app/commands.hpp"

namespace echosim::app {

bool output_folder_exists(const char* command, const char* option, const std::filesystem::path& path)
{
    const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    if (std::filesystem::is_directory(parent)) return true;
    std::fprintf(stderr, "echosim %s: %s %s: folder %s does not exist\n", command, option, path.c_str(), parent.c_str());
    return false;
}

}  // namespace echosim::app

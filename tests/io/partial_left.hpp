// Whether a writer left its partial file (io/partial_file.hpp: PATH.echosim-partial-PID-XXXXXX)
// beside the file it wrote.
#pragma once

#include <filesystem>
#include <string>

#include "io/partial_file.hpp"

namespace echosim::test {

inline bool partial_left_beside(const std::filesystem::path& path)
{
    const std::string head = path.filename().string() + io::kPartialMarker;
    for (const auto& e : std::filesystem::directory_iterator(path.has_parent_path() ? path.parent_path() : "."))
        if (e.path().filename().string().rfind(head, 0) == 0) return true;
    return false;
}

}  // namespace echosim::test

#include "core/assets.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace echosim {

std::filesystem::path asset_path(std::string_view relative)
{
    std::string looked;
    const char* roots[] = {std::getenv("ECHOSIM_ASSETS"), ECHOSIM_SOURCE_ASSET_DIR};
    for (const char* root : roots) {
        if (!root || !*root) continue;
        const std::filesystem::path p = std::filesystem::path(root) / relative;
        if (std::filesystem::exists(p)) return p;
        looked.append(" ").append(p.string());
    }
    throw std::runtime_error("asset '" + std::string(relative) + "' not found (looked in:" + looked +
                             "); set ECHOSIM_ASSETS to the assets folder");
}

}  // namespace echosim

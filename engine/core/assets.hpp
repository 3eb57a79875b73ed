// Where the shipped data (assets/) are found at run time: $ECHOSIM_ASSETS when set, else the
// source tree the binary was built from (echosim runs from its build folder; there is no install).
#pragma once

#include <filesystem>
#include <string_view>

namespace echosim {

// The path of an asset, e.g. asset_path("models/thigh.json"). Throws std::runtime_error naming
// the places looked in when it is not there.
std::filesystem::path asset_path(std::string_view relative);

}  // namespace echosim

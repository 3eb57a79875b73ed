// The stations' images, as the report's files name them (StationResult::image_png, relative to the
// report's folder), read for embedding. A name is taken only when it stays inside the folder (not
// absolute, no ".."), names a regular file of a sane size and holds a PNG: a report never inlines
// some other file of the machine because a path said so.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace echosim::exam {

inline constexpr std::uintmax_t kMaxStationImageBytes = 64u << 20;  // far above a 1080p PNG

struct StationImage {
    std::vector<std::uint8_t> png;  // empty when not read
    std::string why;                // when not read: what was wrong ("not found", "not a PNG", ...)
};

// `relative` under `dir`, or an empty path when the name leaves the folder or is empty.
std::filesystem::path station_image_path(const std::filesystem::path& dir, const std::string& relative);

StationImage read_station_image(const std::filesystem::path& dir, const std::string& relative);

}  // namespace echosim::exam

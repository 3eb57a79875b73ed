#include "exam/report_images.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>

namespace echosim::exam {

std::filesystem::path station_image_path(const std::filesystem::path& dir, const std::string& relative)
{
    const std::filesystem::path rel(relative);
    if (relative.empty() || rel.is_absolute() || rel.has_root_name() || rel.has_root_directory()) return {};
    for (const auto& part : rel)
        if (part == "..") return {};
    return dir / rel;
}

StationImage read_station_image(const std::filesystem::path& dir, const std::string& relative)
{
    StationImage out;
    if (relative.empty()) {
        out.why = "no image";
        return out;
    }
    const std::filesystem::path path = station_image_path(dir, relative);
    if (path.empty()) {
        out.why = "refused: the name leaves the report's folder";
        return out;
    }
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) {
        out.why = "not found";
        return out;
    }
    if (!std::filesystem::is_regular_file(status)) {
        out.why = "not a regular file";
        return out;
    }
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec || size > kMaxStationImageBytes) {
        out.why = ec ? "cannot read its size: " + ec.message() : "larger than " + std::to_string(kMaxStationImageBytes >> 20) + " MiB";
        return out;
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()))) {
        out.why = "cannot read it";
        return out;
    }
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin())) {
        out.why = "not a PNG";
        return out;
    }
    out.png = std::move(bytes);
    return out;
}

}  // namespace echosim::exam

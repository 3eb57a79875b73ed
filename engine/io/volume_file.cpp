#include "io/volume_file.hpp"

#include "io/text_fields.hpp"

#include <array>
#include <fstream>
#include <string>
#include <string_view>

namespace echosim::io {

Volume read_volume(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    // the first line, or as much of it as tells the formats apart
    std::ifstream in = text::open_binary<VolumeFileError>(path);
    std::array<char, 256> head{};
    in.read(head.data(), std::streamsize(head.size()));
    const std::string_view start(head.data(), std::size_t(in.gcount()));
    const std::string_view first_line = start.substr(0, start.find('\n'));
    if (start.starts_with("NRRD")) return read_nrrd(path, memory_budget_bytes);
    if (first_line.find('=') != std::string_view::npos || text::trim(first_line).empty())
        return read_metaimage_volume(path, memory_budget_bytes);
    text::fail<VolumeFileError>(path, "neither a NRRD file (magic 'NRRD000N') nor a MetaImage one ('Name = Value' lines): " +
                                          text::quote_text(first_line));
}

void write_volume(const std::filesystem::path& path, const Volume& volume, bool compressed)
{
    const std::string ext = text::lower(path.extension().string());
    if (ext == ".nrrd") write_nrrd(path, volume, compressed);
    else if (ext == ".mha" || ext == ".mhd") write_metaimage_volume(path, volume, compressed);
    else
        text::fail<VolumeFileError>(path, "write a volume as .nrrd, .mha (MetaImage) or .mhd (MetaImage header with a .raw "
                                          "beside it), not " + (ext.empty() ? std::string("a name without extension") : ext));
}

}  // namespace echosim::io

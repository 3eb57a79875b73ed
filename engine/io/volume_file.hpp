// Volumes in either of the formats 3D Slicer, ITK and PLUS exchange: NRRD (io/nrrd.hpp) and
// MetaImage (io/metaimage.hpp). Reading tells them apart by the file's first bytes, whatever its
// name; writing goes by the name's extension.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "core/printable_text.hpp"
#include "io/metaimage.hpp"
#include "io/nrrd.hpp"

namespace echosim::io {

// A file that is neither format, or a name whose extension says no format.
class VolumeFileError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// NRRD when the file starts with the magic "NRRD", MetaImage when its first line is `Name = Value`.
// Throws NrrdError, MetaImageError or VolumeFileError (all std::runtime_error), naming the file.
Volume read_volume(const std::filesystem::path& path, std::uint64_t memory_budget_bytes = default_nrrd_memory_budget);

// .nrrd: NRRD, gzip when `compressed`; .mha: MetaImage with its data; .mhd: MetaImage header with the
// data beside it (STEM.raw, or STEM.zraw compressed). Extensions in any case. Throws VolumeFileError
// naming the allowed extensions for any other, else what write_nrrd or write_metaimage_volume throw.
void write_volume(const std::filesystem::path& path, const Volume& volume, bool compressed);

}  // namespace echosim::io

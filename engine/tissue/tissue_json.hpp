// The tissue model file (DESIGN.md §3): JSON with the mesh, lambda, mu, per-node a, b and masses,
// the 64 fitted sample parameters it was built from, provenance and fit statistics. Units are in
// the field names. Reading validates every field and names the file and field it rejects.
#pragma once

#include <filesystem>
#include <stdexcept>

#include "core/printable_text.hpp"
#include "tissue/tissue_model.hpp"

namespace echosim::tissue {

class ModelFileError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// Written through a temporary file and renamed, so a failed write never leaves a broken model.
void write_tissue_model(const std::filesystem::path& path, const TissueModel& model);
TissueModel read_tissue_model(const std::filesystem::path& path);

}  // namespace echosim::tissue

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

// The simulator builds a model's nodes and springs from its `samples` on its own leg, at whatever
// refinement it runs; the file's `nodes` and `springs_i_j_rest_mm` are that build at the file's
// refinement, written for other tools. A file whose nodes say otherwise (edited by hand, or made on
// another leg) would be silently overruled, so it is refused: throws ModelFileError naming the file
// and the first field of `read` that differs from `rebuilt` (build_tissue_model of read.samples at
// read.refine on our leg) by more than 1e-6 relative.
void check_derived_fields(const std::filesystem::path& path, const TissueModel& read, const TissueModel& rebuilt);

}  // namespace echosim::tissue

// Coordinate frames and the transforms between them, as the PLUS toolkit keeps them: a recording
// holds some (ProbeToTracker, ReferenceToTracker per frame), the device-set configuration others
// (the ImageToProbe calibration), and what reconstruction needs is a chain of them, e.g.
//   ImageToReference = (ReferenceToTracker)^-1 * ProbeToTracker * ImageToProbe.
// The repository finds the shortest chain between two frames through products and inverses; a
// transform `AToB` maps coordinates in frame A to frame B. A chain is valid only when every link
// is; when there is no chain, the error says which frames each end reaches and so which transform
// is missing.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/printable_text.hpp"

namespace echosim::io {

class TransformError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// "ProbeToTracker" -> {"Probe", "Tracker"}: split at the one "To" followed by a capital letter, as
// PLUS names transforms. nullopt when there is none or more than one ("StylusToToolToTracker").
std::optional<std::pair<std::string, std::string>> split_transform_name(std::string_view name);

// Every entry finite; the last row 0 0 0 1 (points map to points, no projection). What every
// reader of transforms (sequences, configurations, the repository) checks.
bool all_finite(const glm::dmat4& m);
bool is_affine(const glm::dmat4& m);

struct FrameTransform {
    glm::dmat4 matrix{1.0};  // maps `from` coordinates to `to` coordinates
    bool valid = true;       // false: the tracker said INVALID, MISSING, ... for it
};

class TransformRepository {
public:
    // Sets (or replaces) the transform from `from` to `to`; one already given the other way round
    // is replaced too, so the repository never holds two disagreeing answers. Throws TransformError
    // when `from` == `to`, a name is empty, or the matrix is not a finite affine transform.
    void set(const std::string& from, const std::string& to, const glm::dmat4& matrix, bool valid = true);

    // The chain's product, or nullopt when no chain joins the two frames. Throws TransformError
    // when a link that must be inverted is singular.
    std::optional<FrameTransform> find(std::string_view from, std::string_view to) const;

    // As find, but throws TransformError saying which transform is missing when there is no chain.
    FrameTransform get(std::string_view from, std::string_view to) const;

    // Whether any transform held starts or ends in `frame`.
    bool knows(std::string_view frame) const;

    // The transforms held, as "FromToTo" names in the order they were first set.
    std::vector<std::string> names() const;

private:
    struct Link {
        std::string from, to;
        FrameTransform transform;
    };
    std::vector<std::string> reachable(std::string_view frame) const;
    std::vector<Link> links_;
};

}  // namespace echosim::io

// Coordinate frames and the transforms between them, as the PLUS toolkit keeps them: a recording
// holds some (ProbeToTracker, ReferenceToTracker per frame), the device-set configuration others
// (the ImageToProbe calibration), and what reconstruction needs is a chain of them, e.g.
//   ImageToReference = (ReferenceToTracker)^-1 * ProbeToTracker * ImageToProbe.
// The repository finds the shortest chain between two frames through products and inverses; a
// transform `AToB` maps coordinates in frame A to frame B. A chain is valid only when every link
// is; when there is no chain, the error says which frames each end reaches and so which transform
// is missing.
// Cost: set and knows are O(log n) in the n transforms held; a search visits each transform of the
// frames it reaches once, O(n log n) at worst; copies are O(n). (80,000 transforms were quadratic
// before, over a minute: issue 34.)
#pragma once

#include <cstddef>
#include <map>
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

// Whether the 3x3 part cannot be inverted: a column of (almost) no length beside the others, or
// columns (almost) in one plane, judged by angle and relative length, whatever the units.
bool is_singular(const glm::dmat4& m);
// Whether columns 0 and 1 (an image's pixel steps) are (almost) parallel or of no length: the
// image's plane maps to a line or a point.
bool flattens_plane(const glm::dmat4& m);

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

    // One link of a chain: the transform held as from -> to, taken forward or inverted.
    struct Step {
        std::string from, to;  // as held
        bool forward = true;
    };
    // The shortest chain of links from `from` to `to` (empty for a frame to itself), or nullopt
    // when none joins them. It depends only on which transforms are held, not on their matrices, so
    // it can be kept and reused (product) while matrices change.
    std::optional<std::vector<Step>> chain(std::string_view from, std::string_view to) const;

    // The chain's product. Throws TransformError naming the link when a valid link that must be
    // inverted, or any valid link after the chain's first, is singular (is_singular), or when the
    // first flattens the from-frame's x-y plane (flattens_plane): the first may drop the third axis
    // (an image has no thickness), every later one is a motion between solid frames.
    FrameTransform product(const std::vector<Step>& chain) const;

    // The chain's product, or nullopt when no chain joins the two frames; throws as product.
    std::optional<FrameTransform> find(std::string_view from, std::string_view to) const;

    // As find, but throws TransformError saying which transform is missing when there is no chain.
    FrameTransform get(std::string_view from, std::string_view to) const;

    // Whether any transform held starts or ends in `frame`.
    bool knows(std::string_view frame) const;

    // The transforms held, as "FromToTo" names in the order they were first set.
    std::vector<std::string> names() const;

    // The transform held between the two frames, either way round (nullptr when none), and whether
    // it is held as from -> to.
    const FrameTransform* held(std::string_view from, std::string_view to, bool* forward = nullptr) const;

private:
    struct Link {
        std::string from, to;
        FrameTransform transform;
    };
    using Key = std::pair<std::string, std::string>;  // the two frame names, in order: either way round
    static Key key(std::string_view a, std::string_view b);
    std::vector<std::string> reachable(std::string_view frame) const;
    std::vector<Link> links_;                                               // in the order first set
    std::map<Key, std::size_t, std::less<>> index_;                         // -> links_
    std::map<std::string, std::vector<std::size_t>, std::less<>> touching_;  // frame -> links_ that start or end there
};

}  // namespace echosim::io

// The probe's indentation as the image's deform stage takes it (echo::ColumnProfile): for each
// column of the image, where the skin lay before the probe pressed and how far the simulated tissue
// has moved it along the beam, read from the tissue nodes of one physics snapshot. The nodes under
// the face are weighted by a Gaussian of their lateral distance to the column (about the node
// spacing wide) and of their distance across the face (its half thickness), so the profile follows
// the simulated surface along the array, not one scalar.
#pragma once

#include <span>
#include <vector>

#include "core/pose.hpp"
#include "echo/echo_frame.hpp"
#include "physics/compiled_model.hpp"

namespace echosim::session {

class IndentationProfile {
public:
    explicit IndentationProfile(const physics::CompiledModel& model);

    // `face`: the pressed probe's face; `positions`: 3 per tissue node [mm] (a snapshot's). One
    // profile per column of `plane`. A column with no tissue node near it (the probe off the
    // simulated patch) gets the skin where the face rests on it and no shift.
    void compute(const Pose& face, double press_mm, std::span<const float> positions, const echo::ImagePlane& plane,
                 std::vector<echo::ColumnProfile>& out) const;

    double node_spacing_mm() const { return spacing_; }

private:
    std::vector<glm::vec3> rest_;
    double spacing_ = 1.0;  // [mm] between neighbouring nodes
    mutable std::vector<glm::vec4> near_;  // scratch: nodes under the face (x, z, rest y, shift) in the probe frame
};

}  // namespace echosim::session

// A smooth generalised tube: cross-sections given at a few stations along an axis and interpolated
// (Catmull-Rom) in between. The limbs, the pelvis, the feet and the probe are all tubes. The surface
// is a function of (t, theta): t in [0, stations-1] runs along the stations, theta in [0, 2 pi)
// around, starting at +e1 and turning towards +e2. The exam patch samples the same function, so it
// fits the hole left for it in the leg exactly.
#pragma once

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/mesh.hpp"

namespace echosim::scene {

struct Station {
    glm::vec3 center;  // [mm]
    // half-widths [mm] towards +e1, -e1, +e2, -e2: a limb's cross-section is not symmetric
    float r_pos1, r_neg1, r_pos2, r_neg2;
    float exponent = 2.0f;  // super-ellipse exponent: 2 is an ellipse, larger is squarer
};

struct Tube {
    glm::vec3 e1{1, 0, 0};
    glm::vec3 e2{0, 1, 0};
    std::vector<Station> stations;

    float t_max() const { return float(stations.size() - 1); }
    Station at(float t) const;
    glm::vec3 point(float t, float theta) const;
    glm::vec3 outward_normal(float t, float theta) const;
};

enum class Cap { none, flat, pointed };

struct TubeMeshOptions {
    int rings_per_span = 8;  // rings between two stations
    int segments = 64;       // vertices around
    glm::vec3 color{0.8f};
    Cap start = Cap::pointed;
    Cap end = Cap::pointed;
    glm::vec3 flat_cap_color{0.8f};
    // cells (ring i to i+1, segment j to j+1) for which this returns true are left out
    std::function<bool(int ring, int segment)> skip_cell;
};

Mesh build_tube(const Tube& tube, const TubeMeshOptions& options);

}  // namespace echosim::scene

// What the simulation knows about a station, which the trainee's probe is judged against
// (STYLE.md 16: the simulation's truth is the judge, never a guess from the image): where the vein
// runs under it, where its artery and the great saphenous vein are, and whether the vein holds a
// thrombus there. Made from the case's phantom (exam/course_truth.hpp) once per exam.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/pose.hpp"
#include "echo/anatomy.hpp"

namespace echosim::exam {

// A vessel's axis near the station: a point on it and its unit direction [world mm].
struct VesselAxis {
    glm::dvec3 centre{0.0};
    glm::dvec3 direction{0.0, 0.0, 1.0};
    double radius_mm = 0;  // lumen radius at rest
};

struct StationTruth {
    std::string name;
    echo::VeinSegment segment = echo::VeinSegment::cfv;
    double s_cm = 0;
    VesselAxis vein;
    VesselAxis artery;                 // the artery beside it (radius 0: none modelled)
    VesselAxis saphenous;              // the great saphenous vein when it is within reach (radius 0: not)
    bool thrombosed = false;           // a thrombus in the vein at this station
    bool mimic_nearby = false;         // a lymph node within a probe's width
    Pose ideal_probe;                  // transverse, on the skin right above the vein
};

}  // namespace echosim::exam

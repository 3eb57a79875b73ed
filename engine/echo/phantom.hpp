// The anatomical phantom of the thigh under the exam patch (DESIGN.md §1, "ultrasound data"):
// analytic shapes in the limb's own cross-section, so they line up with the rendered leg and the
// tissue model's patch (both sample scene::LegModel's exam limb). For any world point (LPS mm) it
// answers which tissue is there. Three cases: healthy; acute DVT (a distended femoral vein full of
// hypo-echoic thrombus); chronic DVT (a smaller lumen, a thick wall, a partly organised, echogenic
// thrombus).
//
// Where things are, in the proximal right thigh (z from 0 at the groin down): skin 1.6 to 2.2 mm,
// fat 6 to 18 mm, a fascia, then muscle; the common/superficial femoral artery (7.5 mm) and, just
// medial and deeper, the femoral vein (11 mm) at 2 to 4 cm depth under the anterior-medial patch;
// the great saphenous vein (4 mm) in the fat, medially; the femur (26 mm, cortex 4 mm) deeper and
// a little lateral of the vessels, casting an acoustic shadow.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/leg.hpp"

namespace echosim::echo {

enum class Tissue : std::uint8_t {
    outside = 0,
    skin = 1,
    fat = 2,
    fascia = 3,
    muscle = 4,
    artery_lumen = 5,
    artery_wall = 6,
    vein_lumen = 7,
    vein_wall = 8,
    thrombus = 9,
    saphenous_lumen = 10,
    bone_cortex = 11,
    bone_marrow = 12,
    organised_thrombus = 13,  // chronic: partly organised, echogenic
};
inline constexpr int kTissueCount = 14;
const char* tissue_name(Tissue t);

enum class Case { healthy, dvt_acute, dvt_chronic };
const char* case_name(Case c);
Case parse_case(const std::string& name);  // "healthy", "dvt-acute", "dvt-chronic"; throws naming the value

// A vessel's cross-section at one level of the thigh.
struct VesselSection {
    glm::dvec3 centre;      // [mm]
    double lumen_radius;    // [mm]
    double wall;            // wall thickness [mm]
    double thrombus_radius; // thrombus fills the lumen out to this radius from its own centre (0: none)
    glm::dvec3 thrombus_centre;
};

class Phantom {
public:
    Phantom(const scene::LegModel& leg, Case c);

    Tissue tissue_at(const glm::dvec3& world) const;
    // depth below the skin along the limb's radius [mm] (negative outside)
    double depth_at(const glm::dvec3& world) const;

    VesselSection artery(double z) const;
    VesselSection vein(double z) const;
    VesselSection saphenous(double z) const;
    Case which() const { return case_; }

private:
    struct Section {
        glm::dvec3 centre;
        double r_pos1, r_neg1, r_pos2, r_neg2, exponent;
    };
    Section section(double z) const;  // the limb's cross-section at level z
    static double skin_radius(const Section& s, double theta);
    glm::dvec3 at_depth(double z, double theta, double depth) const;
    VesselSection open_vessel(double z, double theta_deg, double depth, double radius, double wall) const;

    Case case_;
    double z_top_, z_step_;
    std::vector<Section> table_;  // the limb's cross-sections every z_step_ mm
};

}  // namespace echosim::echo

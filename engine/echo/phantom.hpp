// The anatomical phantom of the examined leg (DESIGN.md §1, "ultrasound data"): analytic shapes in
// the limb's own cross-sections, so they line up with the rendered leg and the tissue model's
// window (both sample scene::LegModel's exam limb). For any world point (LPS mm) it answers which
// tissue is there. It builds the whole proximal vein course of the compression exam from an
// Anatomy (echo/anatomy.hpp): the fat, the thrombi per segment and the mimics; the course's
// landmarks, calibres and depths are echo/vein_course.hpp's constants.
//
// What is where (the right leg; the limb's angle theta from medial, 0, towards posterior, 90):
//   - skin 1.6 to 2.2 mm, fat (Anatomy::fat_mm over the CFV at the groin, 12 by default, and in
//     proportion elsewhere: 7 to 18 mm for the default), a fascia, then muscle;
//   - the deep vein with its artery (see vein_course.hpp): CFV, SFJ, bifurcation, FV through the
//     adductor canal under the sartorius (its outline a fascia), adductor hiatus, popliteal vein
//     in the fat of the popliteal fossa, three calf veins and two arteries below the trifurcation;
//     the GSV in the fat from the SFJ to below the knee; the DFV and deep femoral artery diving
//     from the bifurcation;
//   - the femur (26 mm, cortex 4 mm) deep and anterior-lateral of the vessels in the thigh, its
//     condyles at the knee, the tibia and fibula below the joint line, casting acoustic shadows;
//   - thrombi: acute, the vein distended by a fifth and filled with hypo-echoic clot, a partly
//     occlusive one against the deep wall leaving a channel of lumen on the superficial side;
//     chronic, the vein shrunk by a fifth, an organised echogenic clot against its deep wall
//     and a thick, irregular, echogenic, rigid wall (Tissue::scarred_vein_wall). Each starts at its
//     proximal tip (Thrombus::start_cm), a 1.2 mm thread floating in the middle of the lumen that
//     grows to the full clot over its first 1.2 cm, and ends at start + extent;
//   - lymph nodes: an ellipsoid in the deep fat, 10 mm medial of the CFV across the limb (its long axis along the
//     limb, LymphNode::size_mm; 0.6 of it across and 0.44 of it deep), its hypo-echoic cortex
//     Tissue::lymph_node around an echogenic fatty hilum (Tissue::fat).
// A thicker fat moves the deep structures inwards: the muscle compartment shrinks radially
// towards the limb's axis (the skin is the rendered leg's and does not move), the deep vein
// keeping its depth under the fascia (a thick fat adds its excess to the vein's depth) and the
// vessels their sizes and their places beside it, the bones pushed aside where they would cut into
// a vessel; the fat is kept below 60 % of the limb's radius.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/pose.hpp"
#include "echo/anatomy.hpp"
#include "echo/vein_course.hpp"
#include "scene/leg.hpp"

namespace echosim::echo {

// The label map's codes. Their values are stable (volumes and label maps on disk carry them):
// new codes are added at the end.
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
    scarred_vein_wall = 14,   // chronic: a vein's thick, irregular, echogenic, rigid wall
    lymph_node = 15,          // a lymph node's hypo-echoic cortex (its hilum is fat)
};
inline constexpr int kTissueCount = 16;
const char* tissue_name(Tissue t);

enum class Case { healthy, dvt_acute, dvt_chronic };
const char* case_name(Case c);
Case parse_case(const std::string& name);  // "healthy", "dvt-acute", "dvt-chronic"; throws naming the value
// The anatomy of each preset case: healthy, none; dvt-acute, an occlusive acute thrombus from the
// CFV at 2 cm (above the SFJ) on through the FV to 26 cm; dvt-chronic, a chronic one in the FV
// from 6 to 26 cm filling 60 % of its lumen.
Anatomy anatomy_of(Case c);

// A vessel at one level of the limb: its centre where its axis crosses the plane of constant world
// z, its radii across the vessel (square to its direction: an oblique vessel's section of constant
// z is an ellipse, longer by 1 / cos of its angle to the limb's axis).
struct VesselSection {
    glm::dvec3 centre{0.0};   // [mm]
    double lumen_radius = 0;  // [mm]
    double wall = 0;          // wall thickness [mm]
    double thrombus_radius = 0;  // thrombus fills the lumen out to this radius from its own centre (0: none)
    glm::dvec3 thrombus_centre{0.0};
};

struct PhantomOptions {
    double step_mm = 0.5;  // the course is tabulated by level every step_mm along the limb
};

class Phantom {
public:
    Phantom(const scene::LegModel& leg, const Anatomy& anatomy, const PhantomOptions& options = {});
    Phantom(const scene::LegModel& leg, Case c);  // anatomy_of(c)

    Tissue tissue_at(const glm::dvec3& world) const;
    // depth below the skin along the limb's radius [mm] (negative outside)
    double depth_at(const glm::dvec3& world) const;
    const Anatomy& anatomy() const { return anatomy_; }
    // the levels the phantom covers [mm] (world z; outside, tissue_at says outside)
    double z_top() const { return z_top_; }
    double z_bottom() const { return z_bottom_; }

    // --- the course (positions s [cm] as echo/anatomy.hpp says; a deep segment takes any s of the
    // deep vein, kDeepVeinFrom_cm .. kTrifurcation_cm, whichever segment it names) ---
    // Whether s lies on the modelled vein of `segment`.
    bool modelled(VeinSegment segment, double s_cm) const;
    // The vein's section at s, in the plane of constant z through its centre. Throws
    // std::out_of_range naming the segment and its modelled span when s is off it.
    VesselSection vein(VeinSegment segment, double s_cm) const;
    // The artery beside it at the same level: the common or superficial femoral or popliteal artery
    // beside the deep vein, the deep femoral artery beside the DFV; none beside the GSV.
    std::optional<VesselSection> artery(VeinSegment segment, double s_cm) const;
    // The vein's unit direction at s, pointing down the course (increasing s).
    glm::dvec3 vein_direction(VeinSegment segment, double s_cm) const;
    // The world level of the vein's section at s [mm], and the deep vein's s at a level [cm].
    double level_z(VeinSegment segment, double s_cm) const;
    double deep_s_at(double z_mm) const;
    // The probe resting on the skin right above the vein at s, in the transverse plane: the image
    // plane is the plane through the vein's centre square to its direction (+z, the elevation, is
    // the vein's direction, up or down the limb); the face's centre is the skin point of that
    // plane nearest the vein's centre, the beam (+y) from there through the centre (the vein is
    // centred in the image at depth |face - centre|), the array (+x) across. Where the vein runs
    // parallel to the skin the beam is the skin's inward normal; where the limb's surface slopes
    // along the vein (the groin, the knee) or the vein dives, the face is tilted off the skin's
    // tangent plane by that slope (under 12 degrees along the course, except the DFV). The marker
    // end of the array (-x, the image's column 0, the screen's left) is towards the patient's
    // right, as the transverse view is shown: +x has a component towards the patient's left
    // (world +x), as scene::LegModel::probe_rest_pose's on the anterior thigh; so on the medial
    // thigh the marker points anterior, from behind the knee (the popliteal vein is reached from
    // the posterior-medial skin, kPoplitealApproachDeg) lateral. Throws as vein() does.
    Pose transverse_probe_pose(VeinSegment segment, double s_cm) const;
    // Whether the anatomy puts a thrombus in the vein at s (the truth under a station): for a deep
    // segment, any thrombus of the deep vein covering s; for a branch, one of that branch.
    bool thrombosed(VeinSegment segment, double s_cm) const;
    // The lymph nodes' centres [world mm], in Anatomy::lymph_nodes' order.
    std::vector<glm::dvec3> lymph_node_centres() const;

private:
    struct Section {
        glm::dvec2 centre;
        double r_pos1, r_neg1, r_pos2, r_neg2, exponent;
    };
    // A vessel at one level; lumen 0: not there.
    // A vessel at one level: a tube whose radii are across its own direction (its centre moves
    // `slope` mm sideways per mm down the limb), so an oblique vessel's section of constant z is an
    // ellipse and its transverse view a circle.
    struct Ring {
        glm::dvec2 c{0.0};
        glm::dvec2 slope{0.0};   // d(centre)/dz
        double lumen = 0, wall = 0;  // lumen 0: not at this level
        double s = 0;            // the vessel's own s at this level [cm]
        glm::dvec2 clot_c{0.0};
        double clot = 0;
        double clot_from = 0, clot_to = -1;  // the clot's span of s [cm]: outside it, no clot
        double plain_wall = 0;   // the wall outside the clot's span
        Tissue lumen_code = Tissue::vein_lumen, wall_code = Tissue::vein_wall, clot_code = Tissue::thrombus;
        Tissue plain_wall_code = Tissue::vein_wall;
        bool irregular = false;  // a chronic wall
    };
    struct Bone {
        glm::dvec2 c{0.0};
        double r = 0, cortex = 0;
    };
    struct Ellipse {  // in the level's plane: half-axes along the limb's radius at `dir` and across it
        glm::dvec2 c{0.0}, dir{1.0, 0.0};
        double radial = 0, across = 0;
    };
    enum Vessel : int { deep_vein, deep_artery, gsv, dfv, dfa, calf_vein0, calf_vein1, calf_vein2, calf_artery0, calf_artery1, kVessels };
    struct Level {
        double z = 0;
        Section limb{};
        Ring ring[kVessels];
        Bone bone[3];         // femur, tibia, fibula
        Ellipse sartorius;    // its outline is a fascia
        Ellipse fossa_fat;    // the popliteal fossa's fat around its vessels
        double theta_vein = 0;  // the deep vein's angle around the limb [rad]
        double ratio = 1;       // the muscle compartment's radial scale for this patient's fat
    };
    struct Node {
        glm::dvec3 c{0.0};
        glm::dvec2 dir{1.0, 0.0};  // the limb's outward radius at it
        double along = 0, across = 0, radial = 0;  // half-axes [mm]
    };
    Section section(double z) const;  // the limb's cross-section at level z
    static double skin_radius(const Section& s, double theta);
    // the fat's thickness [mm] at level z and angle theta, where the skin is `radius` from the axis
    double fat_mm(double z, double theta, double radius) const;
    glm::dvec2 at_depth(const Section& s, double theta, double depth) const;
    const Level& level(std::size_t i) const { return levels_[i]; }
    double index_at(double z) const;  // fractional level index
    // the course at level i for a fat `fat_scale` times the reference's, with `thrombi` (none: the
    // reference course, by which the branches' s are measured)
    Level build_level(std::size_t i, double fat_scale, const std::vector<Thrombus>* thrombi) const;
    void place_bones();
    Ring ring_at(Vessel v, double z) const;  // interpolated between levels
    static Ring blend(const Ring& a, const Ring& b, double w);
    double z_of(VeinSegment segment, double s_cm) const;
    void check_modelled(VeinSegment segment, double s_cm) const;
    VesselSection section_of(const Ring& r, double z) const;

    Anatomy anatomy_;
    double fat_scale_;
    double z_top_, z_bottom_, step_;
    std::vector<Section> limbs_;   // the limb's cross-sections every step_ mm from z_top_ down
    std::vector<Level> levels_;    // the course at the same levels
    std::vector<double> deep_s_;   // the deep vein's s [cm] by level
    std::vector<double> gsv_s_, dfv_s_;  // the branches' s [cm] by level (-1 above their junctions)
    double z_sfj_ = 0, z_bifurcation_ = 0, z_artery_bifurcation_ = 0, z_trifurcation_ = 0;  // [mm]
    std::vector<Node> nodes_;
};

}  // namespace echosim::echo

// The proximal vein course the phantom builds (echo/phantom.hpp), as numbers: where its landmarks
// are along the deep vein, each segment's span, the calibres along it and the depths it lies at.
// One source for these facts: the phantom builds from them, the tests measure the phantom's labels
// against them, and the exam's case files (exam/course_limits.hpp) point at them.
//
// Positions are s [cm] (echo/anatomy.hpp): along the deep vein from the inguinal ligament (s = 0,
// the groin crease, world z = 0) down the common femoral vein (CFV), the femoral vein (FV) from the
// bifurcation and the popliteal vein from the adductor hiatus; the great saphenous vein (GSV) and
// the deep femoral vein (DFV) have their own s from their junctions. s is the arc length of the
// reference patient's vein (Anatomy's default fat, 12 mm); the same s is the same level of the limb
// for every patient (a thicker fat moves the vein deeper, not up or down the thigh).
//
// Where the course runs (the right thigh, the limb's angle theta from medial towards posterior:
// 0 medial, 90 posterior, 180 lateral, 270 anterior; world z from 0 at the groin down):
//   - CFV just below the ligament, anterior-medial (theta 312), 29 mm deep, the common femoral
//     artery lateral to it; the SFJ 3 cm below, the GSV joining from medial and superficial (the
//     "Mickey Mouse" view: the CFV the head, the artery and the GSV its ears);
//   - the bifurcation 5 cm below: the DFV and the deep femoral artery leave deep and lateral (the
//     artery divides 1 cm above the vein) and are modelled over kDfvModelled_cm;
//   - the FV down the thigh, turning medial and deeper (theta 312 to 350, depth 31 to 44 mm) under
//     the sartorius in the adductor canal, its artery crossing over it from lateral to in front;
//   - the adductor hiatus at s = 35 (z about -345): the vessels pass behind the femur into the
//     popliteal fossa;
//   - the popliteal vein behind the knee (the joint line at z = -440), superficial to its artery
//     seen from the back, 24 to 27 mm under the posterior-medial skin, down to the trifurcation
//     (s = 50, z about -485) where it ends in three calf veins;
//   - the GSV in the fat, medially, from the SFJ down to the posterior-medial knee.
// The popliteal fossa is reached from the posterior-medial skin, 25 degrees medial of straight
// posterior (theta about 65: kPoplitealApproachDeg): the vessels lie there, so the skin point
// nearest the popliteal vein is there, 5 to 10 mm above the table top (the probe may pass through
// the table in this simulator).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "echo/anatomy.hpp"

namespace echosim::echo {

// Landmarks along the deep vein [cm from the inguinal ligament].
inline constexpr double kInguinalLigament_cm = 0.0;
inline constexpr double kSfj_cm = 3.0;             // the saphenofemoral junction (on the CFV)
inline constexpr double kBifurcation_cm = 5.0;     // the CFV divides into the FV and the DFV
inline constexpr double kArteryBifurcation_cm = 4.0;  // the common femoral artery divides, a little above
inline constexpr double kAdductorHiatus_cm = 35.0;    // the FV becomes the popliteal vein
inline constexpr double kPoplitealFossa_cm = 42.0;    // the popliteal vein behind the knee (z about -405)
inline constexpr double kTrifurcation_cm = 50.0;      // the popliteal vein ends at the calf veins
// Where the deep vein is modelled: from under the drape above the ligament to the trifurcation.
inline constexpr double kDeepVeinFrom_cm = -1.5;
// The branches, modelled over this much of their own s from their junctions [cm] (the DFV then
// tapers away within 1.5 cm more).
inline constexpr double kGsvModelled_cm = 40.0;
inline constexpr double kDfvModelled_cm = 6.5;
// The world level of the inguinal ligament and of the knee's joint line [mm].
inline constexpr double kLigamentZ_mm = 0.0;
inline constexpr double kKneeJointZ_mm = -440.0;
// The popliteal vessels' angle around the limb: posterior-medial [deg, 0 medial, 90 posterior].
inline constexpr double kPoplitealApproachDeg = 65.0;

// A segment's span along its own s [cm].
struct SegmentSpan {
    double from_cm, to_cm;
};
SegmentSpan segment_span(VeinSegment s);
// Whether the segment is part of the deep vein (its s the deep vein's), not a branch.
constexpr bool on_deep_vein(VeinSegment s) { return s == VeinSegment::cfv || s == VeinSegment::fv || s == VeinSegment::popliteal; }
// The deep vein's segment at s (cfv above the bifurcation, fv to the hiatus, popliteal below).
VeinSegment deep_segment_at(double s_cm);

// Named places on the course.
enum class Landmark : std::uint8_t {
    inguinal_ligament,  // cfv at 0
    sfj,                // cfv at kSfj_cm
    bifurcation,        // cfv at kBifurcation_cm
    adductor_hiatus,    // fv at kAdductorHiatus_cm
    popliteal_fossa,    // popliteal at kPoplitealFossa_cm
    trifurcation,       // popliteal at kTrifurcation_cm
};
inline constexpr int kLandmarkCount = 6;
struct LandmarkSite {
    VeinSegment segment;
    double s_cm;
};
LandmarkSite landmark_site(Landmark l);
const char* landmark_name(Landmark l);  // "inguinal-ligament", "sfj", "bifurcation", "adductor-hiatus", "popliteal-fossa", "trifurcation"
bool parse_landmark(const std::string& name, Landmark& out);

// The nominal calibres: a lumen's inner diameter [mm] at s of the segment, for the reference
// patient without thrombus (an acute thrombus distends the vein, a chronic one shrinks it):
//   deep vein: CFV 13 at the ligament to 12 at the bifurcation; FV 9.5 to 8.5 at the hiatus;
//   popliteal 8.5 to 7 at the trifurcation; GSV 4.8 at the SFJ to 3.6 at the knee; DFV 7 to 5.5;
//   arteries: common femoral 8.5, superficial femoral 7 to 6.3, popliteal 6.3 to 5.8, deep femoral 6 to 4.5.
// Past a segment's span: the nearest end's value (the DFV: 0 past kDfvModelled_cm + 1.5).
double vein_diameter_mm(VeinSegment segment, double s_cm);
double artery_diameter_mm(VeinSegment segment, double s_cm);  // the artery paired with the vein there; 0 for the GSV

// The clinical ranges the calibres keep to [mm] (issue 31's "typical calibres").
struct Range {
    double lo, hi;
};
inline constexpr std::array<Range, kVeinSegmentCount> kVeinCalibre_mm{{
    {10.0, 14.0},  // cfv
    {3.0, 5.0},    // gsv
    {7.0, 10.0},   // fv
    {4.0, 8.0},    // dfv
    {6.0, 9.0},    // popliteal
}};
// the artery beside each vein: the common and superficial femoral and popliteal arteries, the
// deep femoral artery beside the DFV (none beside the GSV)
inline constexpr std::array<Range, kVeinSegmentCount> kArteryCalibre_mm{{
    {6.0, 9.0},  // cfv
    {0.0, 0.0},  // gsv
    {6.0, 9.0},  // fv
    {4.0, 7.0},  // dfv
    {5.5, 9.0},  // popliteal
}};
// The depth of a vein's centre under the skin nearest it [mm], for the reference patient
// (Anatomy::fat_mm = 12); a thicker fat adds to it.
inline constexpr std::array<Range, kVeinSegmentCount> kVeinDepth_mm{{
    {25.0, 34.0},  // cfv
    {5.0, 30.0},   // gsv: in the fat, diving to the CFV over its first 2.5 cm
    {28.0, 48.0},  // fv
    {35.0, 75.0},  // dfv: going deep
    {20.0, 48.0},  // popliteal (from the posterior-medial skin; deeper at the hiatus)
}};

}  // namespace echosim::echo

// What a case says about the patient's body (DESIGN.md §3, "case"): the fat over the vessels, the
// thrombi written per segment of the deep veins, and the mimics. The phantom (echo/phantom.hpp)
// builds the whole proximal vein course from it; a scenario file (exam/scenario.hpp) fills it.
//
// Where things are along the course: `s_cm` is the distance along the deep vein [cm] from the
// inguinal ligament (s = 0) down the common femoral vein, on through the femoral vein from the
// bifurcation, and on through the popliteal vein from the adductor hiatus. The great saphenous vein
// and the deep femoral vein are measured from their junctions with the deep vein (s along that
// branch). Landmarks (phantom.hpp, VeinCourse) give where each segment starts and ends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace echosim::echo {

enum class VeinSegment : std::uint8_t {
    cfv,        // common femoral vein: inguinal ligament to the femoral bifurcation
    gsv,        // great saphenous vein, from the saphenofemoral junction
    fv,         // femoral vein: bifurcation to the adductor hiatus
    dfv,        // deep femoral vein, from the bifurcation, going deep
    popliteal,  // popliteal vein: adductor hiatus to the trifurcation
};
inline constexpr int kVeinSegmentCount = 5;
const char* segment_name(VeinSegment s);               // "cfv", "gsv", "fv", "dfv", "popliteal"
bool parse_segment(const std::string& name, VeinSegment& out);  // false for an unknown name

enum class ThrombusKind : std::uint8_t {
    acute,    // distended vein, hypo-echoic smooth clot, non-compressible
    chronic,  // small rigid vein, thick irregular echogenic wall, echogenic bands
};
const char* thrombus_kind_name(ThrombusKind k);  // "acute", "chronic"
bool parse_thrombus_kind(const std::string& name, ThrombusKind& out);

// A thrombus in one segment: from `start_cm` (in that segment's own s: the deep vein's s for cfv,
// fv and popliteal, the branch's for gsv and dfv) over `extent_cm` of it. `occlusion` is the
// fraction of the lumen's cross-section it fills (1: occlusive; below 1: partly occlusive, a
// channel of flowing blood beside it that still narrows under pressure).
struct Thrombus {
    VeinSegment segment = VeinSegment::fv;
    ThrombusKind kind = ThrombusKind::acute;
    double start_cm = 0;
    double extent_cm = 0;
    double occlusion = 1.0;
};

// A mimic: an inguinal lymph node (oval, hypo-echoic cortex, echogenic hilum) beside the vein at
// `s_cm` of the deep vein, `size_mm` long, which a trainee must not take for a clot.
struct LymphNode {
    double s_cm = 1.0;
    double size_mm = 15.0;
};

struct Anatomy {
    // the fat's thickness over the common femoral vessels at the groin [mm] (the thigh's default:
    // 12); elsewhere the phantom scales its fat by the same ratio. A large patient: 30 to 45.
    double fat_mm = 12.0;
    std::vector<Thrombus> thrombi;
    std::vector<LymphNode> lymph_nodes;
};

}  // namespace echosim::echo

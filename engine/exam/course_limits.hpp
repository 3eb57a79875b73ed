// Where a case file's positions may lie: each vein segment's span along its s [cm] and the named
// landmarks a station may be written as (echo/anatomy.hpp gives the s convention: the deep vein's
// s from the inguinal ligament for the CFV, the FV and the popliteal vein; the branch's own s from
// its junction for the GSV and the DFV).
//
// The numbers are the course the phantom builds (echo/vein_course.hpp, one source): the reader lets
// a thrombus or a station through only where the phantom models a vein, and a landmark names the
// place where the phantom puts it.
#pragma once

#include <array>
#include <string_view>

#include "echo/anatomy.hpp"
#include "echo/vein_course.hpp"

namespace echosim::exam::course {

// Along the deep vein [cm from the inguinal ligament].
inline constexpr double kSfj_cm = echo::kSfj_cm;           // the saphenofemoral junction, on the CFV
inline constexpr double kBifurcation_cm = echo::kBifurcation_cm;   // the CFV divides into the FV and the DFV
inline constexpr double kHiatus_cm = echo::kAdductorHiatus_cm;       // the adductor hiatus: the FV becomes the popliteal vein
inline constexpr double kPoplitealFossa_cm = echo::kPoplitealFossa_cm;  // the popliteal vein behind the knee
inline constexpr double kTrifurcation_cm = echo::kTrifurcation_cm; // the popliteal vein ends at the calf veins
inline constexpr double kGsvModelled_cm = echo::kGsvModelled_cm;  // the great saphenous vein modelled from the SFJ (down to the knee)
inline constexpr double kDfvModelled_cm = echo::kDfvModelled_cm;   // the deep femoral vein modelled from the bifurcation

// A segment's span in its own s, and what bounds it (for messages).
struct SegmentSpan {
    echo::VeinSegment segment;
    std::string_view name;   // as the file writes it (echo::segment_name)
    std::string_view label;  // as a station's default name writes it
    double begin_cm;
    double end_cm;
    std::string_view begins_at;
    std::string_view ends_at;
};

inline constexpr std::array<SegmentSpan, echo::kVeinSegmentCount> kSegments{{
    {echo::VeinSegment::cfv, "cfv", "CFV", 0.0, kBifurcation_cm, "the inguinal ligament", "the femoral bifurcation"},
    {echo::VeinSegment::gsv, "gsv", "GSV", 0.0, kGsvModelled_cm, "the saphenofemoral junction", "the end of the modelled great saphenous vein"},
    {echo::VeinSegment::fv, "fv", "FV", kBifurcation_cm, kHiatus_cm, "the femoral bifurcation", "the adductor hiatus"},
    {echo::VeinSegment::dfv, "dfv", "DFV", 0.0, kDfvModelled_cm, "the femoral bifurcation", "the end of the modelled deep femoral vein"},
    {echo::VeinSegment::popliteal, "popliteal", "Popliteal", kHiatus_cm, kTrifurcation_cm, "the adductor hiatus", "the trifurcation"},
}};

inline constexpr const SegmentSpan& span_of(echo::VeinSegment s)
{
    for (const SegmentSpan& span : kSegments)
        if (span.segment == s) return span;
    return kSegments[0];  // unreachable: every segment is in the table
}

// Whether `s` is on the deep vein (s from the inguinal ligament), not a branch.
inline constexpr bool on_deep_vein(echo::VeinSegment s)
{
    return s == echo::VeinSegment::cfv || s == echo::VeinSegment::fv || s == echo::VeinSegment::popliteal;
}

// A place a station may name instead of a distance: the phantom's landmarks (the same names and
// places) and the places the protocols compress between them (the groin, mid-thigh, the canal).
struct Landmark {
    std::string_view name;          // as the file writes it: "sfj"
    std::string_view station_name;  // the station's default name: "SFJ"
    echo::VeinSegment segment;
    double s_cm;
    std::string_view what;          // for the instructor (README, schema)
};

inline constexpr std::array<Landmark, 9> kLandmarks{{
    {"inguinal-ligament", "Inguinal ligament", echo::VeinSegment::cfv, 0.0, "the CFV at the inguinal ligament, where the course begins"},
    {"groin", "CFV", echo::VeinSegment::cfv, 1.0, "the common femoral vein at the groin, 1 cm below the inguinal ligament, above the SFJ"},
    {"sfj", "SFJ", echo::VeinSegment::cfv, kSfj_cm, "the saphenofemoral junction (the great saphenous vein joining from medial)"},
    {"bifurcation", "Bifurcation", echo::VeinSegment::cfv, kBifurcation_cm, "the femoral bifurcation: the CFV dividing into the FV and the DFV"},
    {"mid-thigh-fv", "FV mid-thigh", echo::VeinSegment::fv, 20.0, "the femoral vein at mid-thigh"},
    {"adductor-canal", "FV adductor canal", echo::VeinSegment::fv, kHiatus_cm - 2.0, "the femoral vein in the adductor canal, 2 cm above the hiatus"},
    {"adductor-hiatus", "FV adductor hiatus", echo::VeinSegment::fv, kHiatus_cm, "the femoral vein at the adductor hiatus, where it becomes the popliteal vein"},
    {"popliteal-fossa", "Popliteal", echo::VeinSegment::popliteal, kPoplitealFossa_cm, "the popliteal vein behind the knee, superficial to the artery"},
    {"trifurcation", "Trifurcation", echo::VeinSegment::popliteal, kTrifurcation_cm, "the popliteal vein at the calf veins' trifurcation"},
}};

// The protocols' tolerances [cm]: a station within kAtLandmark_cm of the SFJ is at the SFJ; the
// extended protocol's FV stations are at most kExtendedGap_cm apart, the first within it of the
// bifurcation and the last within it of the hiatus ("FV every 2 cm to the adductor canal").
inline constexpr double kAtLandmark_cm = 0.5;
inline constexpr double kExtendedGap_cm = 2.0;

}  // namespace echosim::exam::course

#include "echo/vein_course.hpp"

#include <algorithm>

namespace echosim::echo {
namespace {

constexpr std::array<const char*, kLandmarkCount> kLandmarkNames = {"inguinal-ligament", "sfj",           "bifurcation",
                                                                    "adductor-hiatus",   "popliteal-fossa", "trifurcation"};

double lerp(double a, double b, double w) { return a + (b - a) * w; }
double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
double smooth(double e0, double e1, double x)
{
    const double t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3 - 2 * t);
}

// the deep vein's diameter along it, continuous across the segments: the CFV narrows a little to
// the bifurcation, where the DFV takes its share over 8 mm of the vein
double deep_vein(double s)
{
    const double cfv = lerp(13.0, 12.0, clamp01(s / kBifurcation_cm));
    const double fv = lerp(9.5, 8.5, clamp01((s - kBifurcation_cm) / (kAdductorHiatus_cm - kBifurcation_cm)));
    const double popliteal = lerp(8.5, 7.0, clamp01((s - kAdductorHiatus_cm) / (kTrifurcation_cm - kAdductorHiatus_cm)));
    const double thigh = lerp(cfv, fv, smooth(kBifurcation_cm, kBifurcation_cm + 0.8, s));
    return s < kAdductorHiatus_cm ? thigh : popliteal;
}

double deep_artery(double s)
{
    const double sfa = lerp(7.0, 6.3, clamp01((s - kArteryBifurcation_cm) / (kAdductorHiatus_cm - kArteryBifurcation_cm)));
    const double popliteal = lerp(6.3, 5.8, clamp01((s - kAdductorHiatus_cm) / (kTrifurcation_cm - kAdductorHiatus_cm)));
    const double thigh = lerp(8.5, sfa, smooth(kArteryBifurcation_cm, kArteryBifurcation_cm + 0.6, s));
    return s < kAdductorHiatus_cm ? thigh : popliteal;
}

// the deep femoral branches: narrowing over their modelled length, then tapering away
double deep_femoral(double s, double at_junction, double at_end)
{
    const double d = lerp(at_junction, at_end, clamp01(s / kDfvModelled_cm));
    return d * (1.0 - smooth(kDfvModelled_cm, kDfvModelled_cm + 1.5, s));
}

}  // namespace

SegmentSpan segment_span(VeinSegment s)
{
    switch (s) {
    case VeinSegment::cfv: return {kInguinalLigament_cm, kBifurcation_cm};
    case VeinSegment::gsv: return {0.0, kGsvModelled_cm};
    case VeinSegment::fv: return {kBifurcation_cm, kAdductorHiatus_cm};
    case VeinSegment::dfv: return {0.0, kDfvModelled_cm};
    case VeinSegment::popliteal: return {kAdductorHiatus_cm, kTrifurcation_cm};
    }
    return {0.0, 0.0};
}

VeinSegment deep_segment_at(double s_cm)
{
    if (s_cm < kBifurcation_cm) return VeinSegment::cfv;
    if (s_cm < kAdductorHiatus_cm) return VeinSegment::fv;
    return VeinSegment::popliteal;
}

LandmarkSite landmark_site(Landmark l)
{
    switch (l) {
    case Landmark::inguinal_ligament: return {VeinSegment::cfv, kInguinalLigament_cm};
    case Landmark::sfj: return {VeinSegment::cfv, kSfj_cm};
    case Landmark::bifurcation: return {VeinSegment::cfv, kBifurcation_cm};
    case Landmark::adductor_hiatus: return {VeinSegment::fv, kAdductorHiatus_cm};
    case Landmark::popliteal_fossa: return {VeinSegment::popliteal, kPoplitealFossa_cm};
    case Landmark::trifurcation: return {VeinSegment::popliteal, kTrifurcation_cm};
    }
    return {VeinSegment::cfv, 0.0};
}

const char* landmark_name(Landmark l)
{
    const auto i = std::size_t(l);
    return i < kLandmarkNames.size() ? kLandmarkNames[i] : "?";
}

bool parse_landmark(const std::string& name, Landmark& out)
{
    for (std::size_t i = 0; i < kLandmarkNames.size(); ++i)
        if (name == kLandmarkNames[i]) {
            out = Landmark(i);
            return true;
        }
    return false;
}

double vein_diameter_mm(VeinSegment segment, double s_cm)
{
    switch (segment) {
    case VeinSegment::gsv: return lerp(4.8, 3.6, clamp01(s_cm / kGsvModelled_cm));
    case VeinSegment::dfv: return deep_femoral(std::max(0.0, s_cm), 7.0, 5.5);
    default: return deep_vein(std::clamp(s_cm, 0.0, kTrifurcation_cm));
    }
}

double artery_diameter_mm(VeinSegment segment, double s_cm)
{
    switch (segment) {
    case VeinSegment::gsv: return 0.0;
    case VeinSegment::dfv: return deep_femoral(std::max(0.0, s_cm), 6.0, 4.5);
    default: return deep_artery(std::clamp(s_cm, 0.0, kTrifurcation_cm));
    }
}

}  // namespace echosim::echo

#include "exam/course_truth.hpp"

#include <glm/geometric.hpp>
#include <stdexcept>

#include "core/assets.hpp"

namespace echosim::exam {
namespace {

// A lymph node counts as beside a station when its centre lies within half a probe's width of the
// station's image plane and within the image's width of the vein: it is in the trainee's picture.
constexpr double kMimicNearMm = 20.0;
// The great saphenous vein is judged at a station when it runs within this of the deep vein there
// (at the SFJ and just below it): elsewhere it is too far to be taken for the deep vein.
constexpr double kSaphenousNearMm = 30.0;

VesselAxis axis_of(const echo::VesselSection& s, const glm::dvec3& direction)
{
    return {s.centre, direction, s.lumen_radius};
}

}  // namespace

std::vector<StationTruth> station_truth(const echo::Phantom& phantom, const Scenario& scenario)
{
    std::vector<StationTruth> out;
    out.reserve(scenario.stations.size());
    for (const Station& st : scenario.stations) {
        StationTruth t;
        t.name = st.name;
        t.segment = st.segment;
        t.s_cm = st.s_cm;
        const glm::dvec3 dir = phantom.vein_direction(st.segment, st.s_cm);
        t.vein = axis_of(phantom.vein(st.segment, st.s_cm), dir);
        if (const std::optional<echo::VesselSection> a = phantom.artery(st.segment, st.s_cm)) t.artery = axis_of(*a, dir);
        // the GSV at the same level, when the station's picture holds it
        const double z = t.vein.centre.z;
        if (st.segment != echo::VeinSegment::gsv) {
            for (double s = 0; s <= echo::kGsvModelled_cm; s += 0.1)
                if (phantom.modelled(echo::VeinSegment::gsv, s) && phantom.level_z(echo::VeinSegment::gsv, s) <= z) {
                    const echo::VesselSection g = phantom.vein(echo::VeinSegment::gsv, s);
                    if (glm::length(g.centre - t.vein.centre) <= kSaphenousNearMm)
                        t.saphenous = axis_of(g, phantom.vein_direction(echo::VeinSegment::gsv, s));
                    break;
                }
        }
        t.thrombosed = phantom.thrombosed(st.segment, st.s_cm);
        for (const glm::dvec3& node : phantom.lymph_node_centres())
            if (std::abs(glm::dot(node - t.vein.centre, dir)) <= kMimicNearMm && glm::length(node - t.vein.centre) <= 2 * kMimicNearMm)
                t.mimic_nearby = true;
        t.ideal_probe = phantom.transverse_probe_pose(st.segment, st.s_cm);
        out.push_back(std::move(t));
    }
    return out;
}

std::filesystem::path shipped_trajectory(const std::string& case_id, const std::string& style)
{
    const std::string relative = "cases/trajectories/" + case_id + "." + style + ".csv";
    try {
        return asset_path(relative);
    } catch (const std::runtime_error&) {
        throw std::invalid_argument("assets/" + relative + ": no shipped " + style + " exam for case '" + case_id +
                                    "' (give --trajectory F, or write one with `echosim case plan`)");
    }
}

}  // namespace echosim::exam

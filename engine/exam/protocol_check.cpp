#include "exam/protocol_check.hpp"

#include <cmath>
#include <cstdio>

#include "exam/course_limits.hpp"

namespace echosim::exam {
namespace {

std::string cm(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g cm", v);
    return buf;
}

bool at_sfj(const Station& s)
{
    return s.segment == echo::VeinSegment::cfv && std::abs(s.s_cm - course::kSfj_cm) <= course::kAtLandmark_cm;
}

}  // namespace

ProtocolDefect protocol_defect(Protocol protocol, const std::vector<Station>& stations)
{
    const char* name = protocol_name(protocol);
    // the deep vein's stations in the exam's order, groin to knee
    int previous = -1;
    for (std::size_t i = 0; i < stations.size(); ++i) {
        if (!course::on_deep_vein(stations[i].segment)) continue;
        if (previous >= 0 && stations[i].s_cm <= stations[std::size_t(previous)].s_cm)
            return {int(i), "at " + cm(stations[i].s_cm) + ", not past the station before it on the deep vein ('" +
                                stations[std::size_t(previous)].name + "' at " + cm(stations[std::size_t(previous)].s_cm) +
                                "): list the stations from the groin to the knee, each at its own place, as the exam visits them"};
        previous = int(i);
    }

    int cfv = -1, above_sfj = -1, sfj = -1, popliteal = -1, fv_count = 0, second_fv = -1;
    for (std::size_t i = 0; i < stations.size(); ++i) {
        const Station& s = stations[i];
        if (s.segment == echo::VeinSegment::cfv && cfv < 0) cfv = int(i);
        if (s.segment == echo::VeinSegment::cfv && s.s_cm < course::kSfj_cm - course::kAtLandmark_cm && above_sfj < 0) above_sfj = int(i);
        if (at_sfj(s) && sfj < 0) sfj = int(i);
        if (s.segment == echo::VeinSegment::popliteal && popliteal < 0) popliteal = int(i);
        if (s.segment == echo::VeinSegment::fv && ++fv_count == 2) second_fv = int(i);
    }
    const std::string sfj_at = "within " + cm(course::kAtLandmark_cm) + " of the SFJ at " + cm(course::kSfj_cm);
    if (popliteal < 0) return {-1, std::string("the ") + name + " protocol compresses the popliteal vein: no station on it"};

    switch (protocol) {
    case Protocol::two_point:
        if (cfv < 0) return {-1, "the two-point protocol compresses the CFV at the groin: no station on it"};
        for (std::size_t i = 0; i < stations.size(); ++i)
            if (stations[i].segment == echo::VeinSegment::fv)
                return {int(i), "a station on the FV: the two-point protocol compresses the CFV and the popliteal vein only (write "
                                "\"three-point\" or \"extended\" for an exam of the femoral vein)"};
        return {};
    case Protocol::three_point: {
        if (cfv < 0) return {-1, "the three-point protocol compresses the CFV at the groin: no station on it"};
        // the third point: the SFJ beside a CFV station of its own, or the femoral vein
        const bool third = fv_count >= 1 || (sfj >= 0 && above_sfj >= 0);
        if (!third)
            return {-1, "the three-point protocol adds the SFJ (a station " + sfj_at + ", beside one at the groin above it) or the mid-thigh FV "
                        "to the CFV and the popliteal vein: neither is there"};
        if (second_fv >= 0)
            return {second_fv, "a second FV station: the three-point protocol compresses the FV once at most (write \"extended\" for "
                               "the femoral vein every 2 cm)"};
        return {};
    }
    case Protocol::extended: {
        if (above_sfj < 0)
            return {-1, "the extended protocol starts at the CFV at the groin: no CFV station above the SFJ (below " +
                            cm(course::kSfj_cm - course::kAtLandmark_cm) + ")"};
        if (sfj < 0) return {-1, "the extended protocol compresses the SFJ: no station " + sfj_at};
        // the femoral vein from the bifurcation to the hiatus, no gap wider than the protocol's
        constexpr double slack = 1e-6;  // [cm]
        double last = course::kBifurcation_cm;
        std::string last_name = "the femoral bifurcation";
        for (std::size_t i = 0; i < stations.size(); ++i) {
            if (stations[i].segment != echo::VeinSegment::fv) continue;
            if (stations[i].s_cm - last > course::kExtendedGap_cm + slack)
                return {int(i), "at " + cm(stations[i].s_cm) + ", " + cm(stations[i].s_cm - last) + " past " + last_name + " at " + cm(last) +
                                    ": the extended protocol compresses the femoral vein every " + cm(course::kExtendedGap_cm) + " or closer"};
            last = stations[i].s_cm;
            last_name = "'" + stations[i].name + "'";
        }
        if (course::kHiatus_cm - last > course::kExtendedGap_cm + slack)
            return {-1, "the FV's last station (" + last_name + " at " + cm(last) + ") is " + cm(course::kHiatus_cm - last) +
                            " above the adductor hiatus at " + cm(course::kHiatus_cm) + ": the extended protocol compresses the FV every " +
                            cm(course::kExtendedGap_cm) + " to the adductor canal"};
        return {};
    }
    }
    return {};
}

}  // namespace echosim::exam

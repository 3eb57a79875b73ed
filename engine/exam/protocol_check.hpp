// Whether a case's stations are the exam its protocol names (the clinical protocols, issue 31):
//   two-point:   the CFV at the groin and the popliteal vein; no FV station (the two-point exam
//                does not look at the femoral vein: that is what it misses).
//   three-point: the two-point's, and a third at the SFJ or on the femoral vein (one FV station at
//                most: more is the extended exam).
//   extended:    the CFV above the SFJ, the SFJ, the femoral vein every 2 cm or closer from the
//                bifurcation to the adductor canal (the first FV station within 2 cm of the
//                bifurcation, the last within 2 cm of the hiatus), and the popliteal vein.
// For every protocol, the stations on the deep vein are listed in the order the exam visits them,
// from the groin to the knee (s increasing, no two at one place). Stations on the GSV or the DFV
// are extras any protocol may add (a lesson on pressing the wrong vein).
#pragma once

#include <string>
#include <vector>

#include "exam/scenario.hpp"

namespace echosim::exam {

struct ProtocolDefect {
    int station = -1;  // the index of the station at fault in the list; -1: the list as a whole
    std::string why;   // empty: none
    explicit operator bool() const { return !why.empty(); }
};

ProtocolDefect protocol_defect(Protocol protocol, const std::vector<Station>& stations);

}  // namespace echosim::exam

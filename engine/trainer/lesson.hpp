// A lesson (issue 32): a case examined by one of the clinical protocols at a difficulty. The shipped
// cases list the extended exam's stations; a two-point or three-point lesson keeps the protocol's
// own of them (exam/protocol_check.hpp): two-point, the CFV at the groin and the popliteal vein;
// three-point, those and the SFJ (or, without one, the femoral vein's station nearest mid-thigh).
#pragma once

#include "exam/scenario.hpp"

namespace echosim::trainer {

// How much the trainer helps: the guidance (trainer/guidance.hpp) fades with it, and whether the
// leg map says a call was right.
enum class Difficulty { beginner, intermediate, expert };
const char* difficulty_name(Difficulty d);  // "beginner", "intermediate", "expert"

// The case's scenario with the lesson's stations and protocol. Throws std::invalid_argument when the
// case lacks what the protocol needs (a case without a popliteal station), naming the case.
exam::Scenario lesson_scenario(const exam::Scenario& c, exam::Protocol lesson);

}  // namespace echosim::trainer

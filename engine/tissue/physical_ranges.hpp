// What a thigh's tissue can physically be, for every parameter of the two-layer model: the model
// file's reader and the fit refuse parameters outside these ranges, naming the parameter, so a model
// that would settle for seconds, or not at all (a damping of 65,537 N s/mm, a membrane of
// 1e-128 N/mm), never reaches the physics. The ranges are wide on purpose (orders of magnitude
// around soft tissue's, the shipped thigh well inside); they catch absurd values, not unusual legs.
// All are stated per sample point (one of the 64 measured points, the fit's resolution); a model
// refined r times carries a, b, mu and masses scaled as tissue_model.hpp explains, and is checked
// after scaling back.
#pragma once

#include <limits>
#include <string>

#include "tissue/tissue_model.hpp"

namespace echosim::tissue {

struct PhysicalRange {
    double lo, hi;
    const char* unit;
    const char* what;
};

// The two below are also bounded by the press the simulator allows (session::Session::kMaxPressMm,
// 25 mm): every model inside them pushes back harder the deeper it is pressed, all the way down
// (bench/RESULTS.md "Ranges and the deepest press"). Past them the probe's penalty contact cannot
// hold the tissue: at 10 N/mm with springs bottoming at 27 mm the force peaked at 398 N at 20 mm and
// fell to 380 N at 25 mm; bottoming at 5 mm it fell from 105 N at 15 mm to 41 N, at 1 mm to 0 N.
// 1/b: how hard the tissue pushes back per mm at the first touch (the shipped thigh: 0.15..0.20;
// 2 N/mm is ten times that, a tensed muscle; a patch that stiff pushes back 170 N at 25 mm).
inline constexpr PhysicalRange kRestStiffness{1e-3, 2.0, "N/mm", "rest stiffness 1/b of a sample point's spring"};
// b/a: the compression where the spring bottoms out, the soft tissue between skin and bone used up
// (the shipped thigh: 41..63 mm); a = 0, a spring that never bottoms out, is allowed. At least the
// deepest press over the springs' clamp (physics/forces.hpp, 0.95: 26.3 mm) with room for the skin
// beside the probe: a thigh thinner than 30 mm over its femur is outside what we model. At most a
// kilometre, what a = 0 stands for (tissue_model.cpp): a denormal a (1e-310) made b/a infinite,
// and the interpolation between sample points NaN (0 x infinity), which the physics met.
inline constexpr PhysicalRange kBottomingDepth{30.0, 1e6, "mm", "bottoming depth b/a of a sample point's spring"};
// lambda: the skin's membrane stiffness (the shipped thigh: 5.8e-4). Below 1e-6 N/mm the membrane
// carries nothing a probe could measure: a fit that lands there did not find it.
inline constexpr PhysicalRange kSurfaceStiffness{1e-6, 10.0, "N/mm", "surface spring stiffness lambda"};
// mu: the surface damping (the shipped thigh: 9.1e-4, a damping ratio of 1 on a sample point's
// mass; 0.1 N s/mm is a damping ratio of about 100, a patch that creeps for seconds).
inline constexpr PhysicalRange kSurfaceDamping{0.0, 0.1, "N s/mm", "surface spring damping mu"};
// a sample point's share of skin and subcutaneous mass (the shipped thigh: 0.37..1.65 g)
inline constexpr PhysicalRange kSampleMass{1e-6, 0.1, "kg", "mass of a sample point's share of the skin"};
// a surface spring's rest length (the shipped thigh: 9..19 mm between sample points)
inline constexpr PhysicalRange kSpringRestLength{1e-2, 1e3, "mm", "rest length of a surface spring"};

// "" when `value` lies in `range`, else "VALUE UNIT outside the physical range [LO, HI] UNIT (WHAT)";
// NaN is never in range.
std::string range_defect(const PhysicalRange& range, double value);

struct ParameterDefect {
    std::string field;  // as the model file names it, e.g. "samples.b_mm_per_N[12]"
    std::string why;    // as range_defect says it
    explicit operator bool() const { return !field.empty(); }
};

// The first of a point's spring (a, b [1/N, mm/N], per sample point) outside its range; `field`
// names b's and a's fields with the point's index appended.
ParameterDefect spring_defect(double a, double b, const std::string& a_field, const std::string& b_field);
// The first sample parameter outside its range, or none.
ParameterDefect sample_parameters_defect(const SampleParameters& params);

}  // namespace echosim::tissue

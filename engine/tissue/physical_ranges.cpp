#include "tissue/physical_ranges.hpp"

#include <cstdio>

namespace echosim::tissue {

std::string range_defect(const PhysicalRange& range, double value)
{
    if (value >= range.lo && value <= range.hi) return "";
    char text[256];
    std::snprintf(text, sizeof text, "%g %s outside the physical range [%g, %g] %s (%s)", value, range.unit, range.lo, range.hi,
                  range.unit, range.what);
    return text;
}

ParameterDefect spring_defect(double a, double b, const std::string& a_field, const std::string& b_field)
{
    if (!(b > 0)) return {b_field, std::to_string(b) + " mm/N: must be > 0"};
    if (std::string d = range_defect(kRestStiffness, 1.0 / b); !d.empty()) return {b_field, d};
    if (!(a >= 0)) return {a_field, std::to_string(a) + " 1/N: must be >= 0"};
    if (a > 0)
        if (std::string d = range_defect(kBottomingDepth, b / a); !d.empty()) return {a_field, d};
    return {};
}

ParameterDefect sample_parameters_defect(const SampleParameters& p)
{
    for (std::size_t i = 0; i < p.b.size(); ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        if (ParameterDefect d = spring_defect(p.a[i], p.b[i], "samples.a_per_N" + index, "samples.b_mm_per_N" + index)) return d;
    }
    if (std::string d = range_defect(kSurfaceStiffness, p.lambda); !d.empty()) return {"lambda_N_per_mm", d};
    if (std::string d = range_defect(kSurfaceDamping, p.mu); !d.empty()) return {"mu_Ns_per_mm", d};
    return {};
}

}  // namespace echosim::tissue

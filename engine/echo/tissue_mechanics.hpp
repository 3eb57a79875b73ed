// How each tissue of the label map deforms under the probe (the deform stage's table, one entry per
// tissue code: compute/deform_bindings.h). Values are the soft-tissue literature's orders of
// magnitude for compression at small strain (Young's moduli: fat about 5-10 kPa, relaxed muscle
// about 20-30 kPa transversally, skin about 50-100 kPa, vessel walls hundreds of kPa, bone rigid),
// and the pressures the vessels hold (venous about 10 mmHg supine, arterial diastolic 60-80 mmHg).
#pragma once

#include <array>

#include "deform_bindings.h"
#include "echo/echo_frame.hpp"

namespace echosim::echo {

using kernels::TissueMechanics;
using TissueTable = std::array<TissueMechanics, DEFORM_TISSUE_CODES>;

// The table for a patient's case: the healthy vein collapses once the pressure reaching it exceeds
// the venous pressure; an acute thrombus fills it and hardly compresses; a chronic one is partly
// compressible inside a thick, stiff wall.
TissueTable tissue_mechanics(const PatientCase& patient);

// The paper's linear deformation, for volumes without labels: every code the same compliance.
TissueTable paper_linear_mechanics();

}  // namespace echosim::echo

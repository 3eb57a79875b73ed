// The exam area of the skin as a parametric surface, the interface through which the tissue model
// and the fit's reference thigh take the skin, so that neither depends on the leg mesh that draws it
// (scene::LegModel implements it). (u, v) in [0,1]^2: u along the limb from superior, v around it
// from medial towards anterior. World LPS millimetres.
#pragma once

#include <glm/vec3.hpp>

namespace echosim {

class SkinSurface {
public:
    virtual ~SkinSurface() = default;
    virtual glm::vec3 patch_point(float u, float v) const = 0;   // [mm]
    virtual glm::vec3 patch_normal(float u, float v) const = 0;  // outward, unit
};

}  // namespace echosim

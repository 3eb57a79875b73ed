// What the compute kernels and their CPU twins (engine/echo) share beyond the bindings: the few
// definitions that let one function body compile both as GLSL and as C++. In C++ the GLSL types and
// built-ins come from GLM, which mirrors them (vec3, mat4, clamp, smoothstep, atan(y, x), ...), so
// a function written in the common subset is the kernel's maths and the CPU twin's at once, and a
// test that compares the two checks the plumbing around it (dispatch, bindings, sampling).
#ifndef ECHOSIM_KERNEL_SHARED_H
#define ECHOSIM_KERNEL_SHARED_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>
namespace echosim::kernels {
using uint = std::uint32_t;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::mat4;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::packHalf2x16;
using glm::unpackHalf2x16;
using glm::clamp;
using glm::max;
using glm::min;
using glm::smoothstep;
using glm::sign;
using glm::abs;
using glm::ceil;
using glm::floor;
using glm::mix;
using glm::dot;
using glm::mod;
using std::sqrt;
using std::exp2;
using std::log2;
// GLSL's two-argument atan is atan2
inline float atan(float y, float x) { return std::atan2(y, x); }
}  // namespace echosim::kernels
#define KERNEL_FN inline
#define KERNEL_PRECISE
#else
#define KERNEL_FN
#define KERNEL_PRECISE precise
#endif

#ifdef __cplusplus
namespace echosim::kernels {
#endif

// The image's pixel centres in the probe frame [mm] (echo::ImagePlane): column c at x, across a
// width centred on the probe; row r at depth y from the face.
// `precise` (GLSL): an NVIDIA GPU fuses (c + 0.5) * pixel - width / 2 into one FMA otherwise, and a
// pixel on a voxel's boundary (every other 0.1 mm pixel on a 0.2 mm label grid) then rounds to
// another voxel than the CPU twin's, which is built without FMA contraction
KERNEL_FN float pixel_x(uint c, float pixel_x_mm, float width_mm)
{
    KERNEL_PRECISE float x = (float(c) + 0.5f) * pixel_x_mm - 0.5f * width_mm;
    return x;
}
KERNEL_FN float pixel_y(uint r, float pixel_y_mm)
{
    KERNEL_PRECISE float y = (float(r) + 0.5f) * pixel_y_mm;
    return y;
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif

#endif

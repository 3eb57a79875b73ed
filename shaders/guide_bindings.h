// The practice guides' pipeline (engine/runner/guide_pass.hpp): the vessels' course and the image
// plane drawn see-through over the leg. Included by shaders/guide.vert, shaders/guide.frag and the
// C++ pass, so the two sides cannot disagree on a layout.
#ifndef ECHOSIM_GUIDE_BINDINGS_H
#define ECHOSIM_GUIDE_BINDINGS_H

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace echosim::runner::guide_bindings {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
#endif

// Per draw, as push constants (80 bytes).
struct GuidePush {
    mat4 clip_from_object;  // the camera's view-projection times the object's model matrix
    vec4 colour;            // display values (sRGB-encoded) and the opacity
};

#ifdef __cplusplus
}  // namespace echosim::runner::guide_bindings
#endif
#endif

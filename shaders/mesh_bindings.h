// Bindings of the mesh pipeline, included by shaders/mesh.vert, shaders/mesh.frag and the C++
// scene pass, so the two sides cannot disagree on a layout. std140/std430 agree for these members.
#ifndef ECHOSIM_MESH_BINDINGS_H
#define ECHOSIM_MESH_BINDINGS_H

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace echosim::render::mesh_bindings {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
#endif

#define MESH_FRAME_SET 0
#define MESH_FRAME_BINDING 0

// Per frame, in a uniform buffer.
struct FrameUniforms {
    mat4 view_proj;   // world [mm] to clip
    vec4 eye;         // camera position [mm], w unused
    vec4 key_dir;     // direction the key light travels (unit), w: intensity
    vec4 fill_dir;    // direction the fill light travels (unit), w: intensity
    vec4 sky;         // ambient from the patient's anterior (up), rgb
    vec4 ground;      // ambient from the table side, rgb
};

// Per draw, as push constants (80 bytes: within the 128 every device offers).
struct DrawPush {
    mat4 model;  // object to world
    vec4 tint;   // rgb multiplies the vertex colour; a: glossiness in [0, 1] (gel on the skin, the probe's plastic)
};

#ifdef __cplusplus
}  // namespace echosim::render::mesh_bindings
#endif
#endif

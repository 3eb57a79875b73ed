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
    // world [mm] to the gel's own coordinates: the gel lies on the skin around the probe's face,
    // an ellipse of radius 1 in this map's x and z (the array's and the elevation's directions)
    mat4 gel_from_world;
};

// Per draw, as push constants (96 bytes: within the 128 every device offers).
struct DrawPush {
    mat4 model;  // object to world
    vec4 tint;   // rgb multiplies the vertex colour; a: glossiness in [0, 1] (gel on the skin, the probe's plastic)
    // x: 1 where the glossiness is the gel's, only within the gel's ellipse around the probe
    // (FrameUniforms::gel_from_world) and fading out at its rim, so the skin around it is the
    // matte skin of the rest of the leg; 0: glossy all over (the probe)
    // y: the opacity of a see-through draw (the probe's ghost where the leg or the table hides it:
    // render/scene_pass.hpp); 0: opaque
    vec4 material;
};

#ifdef __cplusplus
}  // namespace echosim::render::mesh_bindings
#endif
#endif

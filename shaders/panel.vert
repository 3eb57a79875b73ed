#version 450
#extension GL_GOOGLE_include_directive : require
#include "panel_bindings.h"

// The quad that fills the viewport the panel pass sets (the panel's rectangle of the target), as a
// triangle strip of PANEL_VERTEX_COUNT corners without vertex buffers. Texture coordinates run from
// (0, 0) at the top-left corner to (1, 1) at the bottom-right: the image's first row on top.
layout(location = 0) out vec2 out_uv;

void main()
{
    vec2 corner = vec2(float(gl_VertexIndex & 1), float(gl_VertexIndex >> 1));
    out_uv = corner;
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);  // Vulkan clip space: y = -1 is the top
}

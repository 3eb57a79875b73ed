#version 450
#extension GL_GOOGLE_include_directive : require
#include "panel_bindings.h"
#include "srgb.glsl"

layout(set = PANEL_IMAGE_SET, binding = PANEL_IMAGE_BINDING) uniform sampler2D image;
// Whether the image's format is sRGB, so the sampler has decoded it already (a table lookup, where
// the decode below is three powers a pixel: on lavapipe, about 1.5 frames/s of the window's 30).
layout(constant_id = 0) const bool SAMPLER_DECODES = false;
// Whether the target's format is sRGB, so it encodes what we write (on lavapipe, an encode per
// pixel written); where it is not, the target takes display values as they are.
layout(constant_id = 1) const bool TARGET_ENCODES = true;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

// The image holds display values (a scanner's grey levels, sRGB-encoded as a PNG is); the target
// shows the image's own bytes. The cheap pairing, and the one echosim's images and targets make
// (image/echo_image_gpu.cpp, gpu/window.cpp, gpu/offscreen.hpp): a UNORM image on a UNORM target,
// the bytes passed through.
void main()
{
    vec3 c = texture(image, in_uv).rgb;
    if (TARGET_ENCODES)
        out_color = vec4(SAMPLER_DECODES ? c : srgb_to_linear(c), 1.0);
    else
        out_color = vec4(SAMPLER_DECODES ? linear_to_srgb(c) : c, 1.0);
}

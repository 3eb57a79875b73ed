#version 450
#extension GL_GOOGLE_include_directive : require
#include "panel_bindings.h"

layout(set = PANEL_IMAGE_SET, binding = PANEL_IMAGE_BINDING) uniform sampler2D image;
// Whether the image's format is sRGB, so the sampler has decoded it already (a table lookup, where
// the decode below is three powers a pixel: on lavapipe, about 1.5 frames/s of the window's 30).
layout(constant_id = 0) const bool SAMPLER_DECODES = false;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

// The image holds display values (a scanner's grey levels, sRGB-encoded as a PNG is). The target
// is an sRGB attachment that encodes what we write, so decode first: the target then shows the
// image's own bytes.
vec3 srgb_to_linear(vec3 c)
{
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

void main()
{
    vec3 c = texture(image, in_uv).rgb;
    out_color = vec4(SAMPLER_DECODES ? c : srgb_to_linear(c), 1.0);
}

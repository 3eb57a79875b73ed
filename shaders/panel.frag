#version 450
#extension GL_GOOGLE_include_directive : require
#include "panel_bindings.h"

layout(set = PANEL_IMAGE_SET, binding = PANEL_IMAGE_BINDING) uniform sampler2D image;

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
    out_color = vec4(srgb_to_linear(texture(image, in_uv).rgb), 1.0);
}

#version 450
#extension GL_GOOGLE_include_directive : require
#include "guide_bindings.h"
#include "srgb.glsl"

layout(push_constant) uniform Push { GuidePush draw; };
// Whether the target's format encodes sRGB itself (then the display colour given is decoded first,
// so the blend happens in linear light and the screen shows the colour asked for).
layout(constant_id = 0) const bool TARGET_ENCODES = true;
layout(location = 0) out vec4 out_color;

void main()
{
    vec3 c = TARGET_ENCODES ? srgb_to_linear(draw.colour.rgb) : draw.colour.rgb;
    out_color = vec4(c, draw.colour.a);
}

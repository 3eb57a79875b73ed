#version 450
#extension GL_GOOGLE_include_directive : require
#include "guide_bindings.h"

layout(push_constant) uniform Push { GuidePush draw; };
layout(location = 0) in vec3 in_position;  // object space [mm]

void main() { gl_Position = draw.clip_from_object * vec4(in_position, 1.0); }

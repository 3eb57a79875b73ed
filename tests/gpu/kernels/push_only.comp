#version 450

// A kernel with push constants and no bindings (no descriptor set to bind before a dispatch). It
// can write nowhere, so a test sees only that it is dispatched, with validation silent.
layout(local_size_x = 1) in;
layout(push_constant) uniform Push { uint value; } push;

void main()
{
    if (push.value == 0xffffffffu) return;
}

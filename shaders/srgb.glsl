// sRGB's transfer function both ways (IEC 61966-2-1), for shaders that write to or read from a
// target or image whose format does not do it for them.
#ifndef ECHOSIM_SRGB_GLSL
#define ECHOSIM_SRGB_GLSL

vec3 srgb_to_linear(vec3 c)
{
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

vec3 linear_to_srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

#endif

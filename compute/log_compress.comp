#version 450
#extension GL_GOOGLE_include_directive : require
#include "log_compress_bindings.h"

// The post stage of the echographic image: log compression of the envelope into 8-bit grey, as a
// scanner's display maps 50-60 dB of echo amplitude onto the screen. The CPU reference in
// engine/echo/log_compress.cpp computes the same expression.
layout(local_size_x = LOG_COMPRESS_GROUP_SIZE) in;
layout(std430, binding = LOG_COMPRESS_ENVELOPE_BINDING) readonly buffer Envelope { float envelope[]; };
layout(std430, binding = LOG_COMPRESS_IMAGE_BINDING) writeonly buffer Image { uint image[]; };
layout(push_constant) uniform Push { LogCompressParams params; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    float amplitude = max(envelope[i], 1e-20);
    float db = 20.0 * log2(amplitude / params.reference) * 0.30102999566 + params.gain_db;  // log10(x) = log2(x) log10(2)
    uint grey = display_grey(db, params.dynamic_range_db);
    image[i] = grey | (grey << 8) | (grey << 16) | (255u << 24);
}

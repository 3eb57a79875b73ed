#version 450
#extension GL_GOOGLE_include_directive : require
#include "sample_volume_bindings.h"

// Samples a volume through its sampler (linear or nearest, clamp to edge) at a grid of points:
// what the slicing kernel will do along each image row.
layout(local_size_x = SAMPLE_VOLUME_GROUP_SIZE, local_size_y = SAMPLE_VOLUME_GROUP_SIZE,
       local_size_z = SAMPLE_VOLUME_GROUP_SIZE) in;
layout(binding = SAMPLE_VOLUME_VOLUME_BINDING) uniform sampler3D volume;
layout(std140, binding = SAMPLE_VOLUME_GRID_BINDING) uniform Grid { SampleGrid grid; };
layout(std430, binding = SAMPLE_VOLUME_OUT_BINDING) writeonly buffer Out { float values[]; };

void main()
{
    uvec3 id = gl_GlobalInvocationID;
    if (any(greaterThanEqual(id, grid.count.xyz))) return;
    vec3 p = grid.origin.xyz + vec3(id) * grid.step.xyz;
    values[id.x + grid.count.x * (id.y + grid.count.y * id.z)] = textureLod(volume, p, 0.0).r;
}

#version 450
#extension GL_GOOGLE_include_directive : require
#include "deform_bindings.h"
#include "slice_bindings.h"

// The slice stage: one invocation per pixel. The grey volume is sampled through a linear sampler
// (the hardware's trilinear filter) at normalised coordinates (index + 0.5) / size; the labels share
// the volume's grid and are fetched at the nearest voxel.
layout(local_size_x = SLICE_GROUP_X, local_size_y = SLICE_GROUP_Y) in;
layout(binding = SLICE_VOLUME_BINDING) uniform sampler3D volume;
layout(binding = SLICE_LABELS_BINDING) uniform usampler3D labels;
layout(std430, binding = SLICE_MAP_BINDING) readonly buffer Map { vec2 map[]; };
layout(std430, binding = SLICE_GREY_BINDING) writeonly buffer Grey { float grey[]; };
layout(std430, binding = SLICE_LABEL_OUT_BINDING) writeonly buffer LabelOut { uint label_out[]; };
layout(push_constant) uniform Push { SliceParams params; };

void main()
{
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= params.columns || px.y >= params.rows) return;
    uint i = px.y * params.columns + px.x;
    float y = (params.flags & SLICE_WARPED) != 0u ? map[i].x : pixel_y(px.y, params.pixel_y_mm);
    vec3 index = vec3(params.probe_to_index * vec4(pixel_x(px.x, params.pixel_x_mm, params.width_mm), y, 0.0, 1.0));
    vec3 size = vec3(textureSize(volume, 0));
    grey[i] = inside_volume(index, size) ? texture(volume, (index + 0.5) / size).r * 255.0 : 0.0;
    if ((params.flags & SLICE_LABELS) != 0u) {
        ivec3 v = ivec3(floor(index + 0.5));
        bool in_map = all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, textureSize(labels, 0)));
        label_out[i] = in_map ? texelFetch(labels, v, 0).r : 0u;
    }
}

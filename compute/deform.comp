#version 450
#extension GL_GOOGLE_include_directive : require
#include "deform_bindings.h"

// The deform stage of the echographic image: one invocation per image column walks it from the skin
// down (deform_column.h, shared line for line with the CPU twin engine/echo/deform_cpu.cpp), in two
// or three dispatches: every column solved on its own (DEFORM_SOLVE); on a GPU its displacements
// spread sideways, an invocation a run of step boundaries (DEFORM_SPREAD_PASS: x the column, y the
// run; deform_bindings.h says why only there); then mapped (DEFORM_MAP).
layout(local_size_x = DEFORM_GROUP_SIZE) in;
// which pass this pipeline runs: a constant, so each pass's pipeline holds its own code only; and
// whether the spread and map passes read what the passes before wrote through the texel views (a
// CPU device's) or as storage (a GPU's: deform_bindings.h says why; the solve pass never sets it)
layout(constant_id = 0) const uint VARIANT = DEFORM_SOLVE;
const uint PASS = VARIANT & (DEFORM_MAP | DEFORM_SPREAD_PASS);
const bool TEXEL_READS = (VARIANT & DEFORM_TEXEL_READS) == DEFORM_TEXEL_READS;
const bool SPREAD_LOADED = (VARIANT & DEFORM_SPREAD_LOADED) == DEFORM_SPREAD_LOADED;
layout(binding = DEFORM_LABELS_BINDING) uniform usampler3D labels;
layout(std430, binding = DEFORM_PROFILE_BINDING) readonly buffer Profile { vec2 profile[]; };
layout(std140, binding = DEFORM_TISSUES_BINDING) uniform Tissues { TissueMechanics tissues[DEFORM_TISSUE_CODES]; };
layout(std430, binding = DEFORM_SCRATCH_BINDING) buffer Scratch { uvec2 scratch[]; };
layout(std430, binding = DEFORM_MAP_BINDING) writeonly buffer Map { vec2 map[]; };
layout(std430, binding = DEFORM_MOVED_BINDING) buffer Moved { float moved[]; };
layout(std430, binding = DEFORM_WALLS_BINDING) buffer Walls { uint walls[]; };
layout(binding = DEFORM_SCRATCH_TEXELS_BINDING) uniform usamplerBuffer scratch_texels;
layout(binding = DEFORM_MOVED_TEXELS_BINDING) uniform samplerBuffer moved_texels;
layout(binding = DEFORM_WALLS_TEXELS_BINDING) uniform usamplerBuffer walls_texels;
layout(std430, binding = DEFORM_SPREAD_BINDING) buffer Spread { float spread[]; };
layout(push_constant) uniform Push { DeformParams params; };

uint deform_label(vec3 index)
{
    ivec3 i = ivec3(floor(index + 0.5));
    ivec3 size = textureSize(labels, 0);
    if (any(lessThan(i, ivec3(0))) || any(greaterThanEqual(i, size))) return 0u;
    uint code = texelFetch(labels, i, 0).r;
    return code < uint(DEFORM_TISSUE_CODES) ? code : 0u;
}
TissueMechanics deform_tissue(uint code) { return tissues[code]; }
vec2 deform_profile(uint column) { return profile[column]; }
// The scratch, the displacements and the wall distances are step-major: the invocations of a group
// (neighbouring columns) walk down side by side, so their entries of a step share cache lines
// (column-major put them max_steps entries apart, a line, and on a CPU device a gather's lane,
// each), and a boundary's neighbours, which deform_spread reads, lie side by side.
uint step_major(uint column, uint step) { return step * params.columns + column; }
vec4 scratch_load(uint column, uint step)
{
    uint i = step_major(column, step);
    return scratch_unpack(TEXEL_READS ? texelFetch(scratch_texels, int(i)).xy : scratch[i]);
}
void scratch_store(uint column, uint step, vec4 v) { scratch[step_major(column, step)] = scratch_pack(v); }
void map_store(uint pixel, vec2 v) { map[pixel] = v; }
float moved_load(uint column, uint boundary)
{
    uint i = step_major(column, boundary);
    return TEXEL_READS ? texelFetch(moved_texels, int(i)).r : moved[i];
}
void moved_store(uint column, uint boundary, float v) { moved[step_major(column, boundary)] = v; }
vec2 walls_load(uint column, uint boundary)
{
    uint i = step_major(column, boundary);
    return unpackHalf2x16(TEXEL_READS ? texelFetch(walls_texels, int(i)).r : walls[i]);
}
void walls_store(uint column, uint boundary, vec2 v) { walls[step_major(column, boundary)] = packHalf2x16(v); }
float spread_load(uint column, uint boundary) { return spread[step_major(column, boundary)]; }
void spread_store(uint column, uint boundary, float v) { spread[step_major(column, boundary)] = v; }
bool spread_loaded() { return SPREAD_LOADED; }

#include "deform_column.h"

void main()
{
    uint c = gl_GlobalInvocationID.x;
    if (c >= params.columns) return;
    if (PASS == DEFORM_SOLVE) deform_column_solve(c, params);
    else if (PASS == DEFORM_SPREAD_PASS)
        for (uint b = gl_GlobalInvocationID.y * DEFORM_SPREAD_RUN; b < (gl_GlobalInvocationID.y + 1u) * DEFORM_SPREAD_RUN; ++b)
            deform_column_spread(c, b, params);
    else deform_column_map(c, params);
}

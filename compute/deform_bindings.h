// Bindings and maths of compute/deform.comp, the deform stage of the echographic image (paper §6.1,
// DESIGN.md §1): where, in the undeformed volume, each pixel of the pressed image comes from. Shared
// with its CPU twin (engine/echo/deform_cpu.cpp) and its dispatcher (engine/image/echo_image_gpu.cpp).
//
// The model, one image column (one lateral position x along the array) at a time, but for the
// sideways spread at the end:
//   - the column starts at the undeformed skin (y = skin_y in the pressed probe's frame, negative
//     above the face) and ends at the image's depth, which the deformation does not move (the bone
//     and the deep tissue hardly move: the tissue model's springs are anchored there), or at its
//     first rigid step (bone), which anchors it as well: what lies below neither moves nor feels
//     the probe;
//   - the skin under the face moved skin_shift [mm] along the beam (from the physics snapshot);
//   - the pressure the probe puts on the skin (its force over the face, from the same snapshot)
//     reaches depth z below the face as the stress under a uniformly loaded rectangle in an elastic
//     half-space (Boussinesq, integrated over the face by Newmark): deep tissue feels less of it;
//     z is where the tissue lies now, its depth at rest less what the tissue above it lost;
//   - a vessel's lumen closes by the pressure it feels: a vein once the pressure exceeds the venous
//     pressure, walls meeting fully; an artery hardly (its own pressure is far higher), and it
//     widens with the pulse;
//   - the solid tissues compress in series under the stress that reaches them, each by its
//     compliance up to a largest strain (skin and fat most, muscle less, bone nothing);
//   - what the pressure and the lumens leave of the skin's shift (the shift is the simulated
//     tissue's; the compliances are the image model's) is taken up by the solids too, so the
//     column's shortening equals the shift and the deep end stays put, past their largest strains
//     where they cannot take it otherwise (a deep press over little soft tissue: in truth it flows
//     out to the sides, which a column cannot show; DEFORM_OVERFLOW_MAX). Where a lumen closes by
//     more than that, the remainder is negative: the tissue above and below it sinks and rises into
//     the space (in truth it also flows in from the sides), stretching the steps near it, the more
//     the nearer (DEFORM_INFLOW_MM);
//   - then, all columns solved, their displacements spread sideways (a second pass): the tissue
//     above a closing vein sinks with it and drags its neighbours along, over a width growing
//     with the distance from the lumen (DEFORM_SPREAD), while the walls, the skin and the deep end
//     stay where their own column puts them, so the walls still meet;
//   - where a lumen closes, the sound no longer crosses that length of weakly attenuating blood: what
//     lies below loses the posterior enhancement it had (a gain in dB carried down the column, and
//     blended with the neighbouring columns' over the beam's width: the enhancement the volume
//     holds fades out at the lumen's edges);
//   - where a lumen's walls meet, their two echoes become one bright line (a gain at the meeting
//     point).
// Without labels the paper's linear deformation applies: one compliance, no decay with depth.
//
// Output, per pixel (column-major within a column walk, stored row-major): vec2(source y [mm] in the
// pressed probe's frame, gain [dB]).
#ifndef ECHOSIM_DEFORM_BINDINGS_H
#define ECHOSIM_DEFORM_BINDINGS_H

#include "kernel_shared.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

// a column an invocation, and only a few hundred columns (deform_columns): small groups share them
// evenly among lavapipe's threads (a group runs on one), which 32 did not (5 groups on 2 threads)
#define DEFORM_GROUP_SIZE 8
#define DEFORM_LABELS_BINDING 0   // usampler3D: tissue codes (a 1-voxel map of 0 without labels)
#define DEFORM_PROFILE_BINDING 1  // vec2 per column: (skin_y [mm], skin_shift [mm])
#define DEFORM_TISSUES_BINDING 2  // uniform: TissueMechanics per tissue code
#define DEFORM_SCRATCH_BINDING 3  // uvec2 per column per walk step, scratch_pack's (the kernel's own working memory)
#define DEFORM_MAP_BINDING 4      // vec2 per pixel: (source y [mm], gain [dB])
#define DEFORM_MOVED_BINDING 5    // float per column per step boundary (max_steps + 1): how far it moved [mm]
#define DEFORM_WALLS_BINDING 6    // uint per column per step boundary: its distances to what fixes it [mm], two half floats
// The same three buffers as texel buffers (R32G32_UINT, R32_SFLOAT, R32_UINT), which the map pass
// reads them through on a CPU device (DEFORM_TEXEL_READS): the solve pass's dispatch wrote them, so
// a plain read-only view sees them. A CPU device fetches a texel for all its lanes at once, where a
// storage buffer's load is a loop over the lanes with a branch each (llvmpipe); the map pass's
// sideways spread makes some twenty loads a step boundary. A GPU reads them as storage: there a
// column's walk is one thread's chain of dependent loads (a few hundred columns, far too few threads
// to hide a load's wait), and a texel fetch goes through the texture unit, whose wait is longer than
// a storage load's from the cache (the H100's 1,000 frames/s were measured with storage reads).
#define DEFORM_SCRATCH_TEXELS_BINDING 7
#define DEFORM_MOVED_TEXELS_BINDING 8
#define DEFORM_WALLS_TEXELS_BINDING 9
// float per column per step boundary: the displacement spread sideways (deform_spread) [mm], the
// spread pass's output, which the map pass reads (a GPU's only: DEFORM_SPREAD_PASS)
#define DEFORM_SPREAD_BINDING 10
#define DEFORM_TISSUE_CODES 16

// how far from a closing lumen the tissue sinking and rising into it stretches (halving distance
// of its share) [mm]: per mm the column's lumens close, and at least
#define DEFORM_INFLOW_PER_MM 0.5f
#define DEFORM_INFLOW_MM 2.0f
// the most of what is left of a step's length that it loses to a column's overflow (a remainder
// the steps' largest strains cannot take: deform_column.h, remainder_level)
#define DEFORM_OVERFLOW_MAX 0.9f
// the sideways spread of the columns' displacements (deform_column.h, deform_spread): its standard
// deviation per mm of distance from a lumen's wall, the skin or the deep end, and its largest [mm];
// and the closure from which a lumen's walls count (they meet: the spread must not part them)
#define DEFORM_SPREAD 0.7f
#define DEFORM_SPREAD_MAX_MM 3.0f
#define DEFORM_MEETING 0.5f
// the width across the beam over which a closing lumen's gain fades out at its edges (deform_column.h,
// deform_gain_band): a Gaussian's standard deviation [mm]
#define DEFORM_GAIN_BLUR_MM 0.6f
// the coapted walls' echo where a lumen's walls meet (deform_column.h, deform_seam_db): its gain at
// the meeting point [dB], how far either side it fades out [mm], and the closure from which a
// lumen's walls touch (a vein that closes less still shows its lumen, dark, between them)
#define DEFORM_SEAM_DB 12.0f
#define DEFORM_SEAM_MM 0.3f
#define DEFORM_SEAM_CLOSURE 0.9f

// The three passes, each a dispatch of its own pipeline (the kernel's specialization constant 0):
#define DEFORM_SOLVE 0u  // each column on its own (deform_column_solve): an invocation a column
#define DEFORM_MAP 1u    // last, the map, from the columns and the spread (deform_column_map): an invocation a column
#define DEFORM_TEXEL_READS 2u  // (with DEFORM_MAP) read the solve's buffers through the texel views
// On a GPU, between them, the displacements spread sideways (deform_column_spread): an invocation a
// run of a column's step boundaries, all at once, so the map pass's walk down a column no longer
// waits at every step on the spread's chain of loads (the neighbours' wall distances, then the
// displacements they say to blend), which made the map the frame's largest cost there (0.70 of an
// H200's 1.54 ms at 1024 x 1024). A CPU device's map computes the spread in its walk, as the CPU
// twin does: there the pass cost more than it saved (lavapipe, 1024 x 1024: 2.2 ms against 1.3).
#define DEFORM_SPREAD_PASS 4u
#define DEFORM_SPREAD_RUN 8u     // the step boundaries an invocation of the spread pass takes (y: runs of them)
#define DEFORM_SPREAD_LOADED 8u  // (with DEFORM_MAP) the spread pass ran: the map reads its spread

#define DEFORM_PAPER_LINEAR 1u  // no labels: one compliance, no decay with depth, no sideways spread

// How one tissue deforms under the stress that reaches it.
struct TissueMechanics {
    float compliance;          // solid: strain per kPa of stress [1/kPa]
    float max_strain;          // solid: the largest strain, in compression and in stretch
    float collapse_onset_kpa;  // lumen: the transmitted pressure where it begins to close [kPa]
    float collapse_width_kpa;  // lumen: the pressure over which it goes on to close fully [kPa] (> 0)
    float max_closure;         // lumen: the fraction of its length it can lose (1: walls meet; 0: not a lumen)
    float pulse_strain;        // lumen: the fraction it widens at the peak of the pulse
    float attenuation;         // one way [dB/cm/MHz]: what the sound loses crossing it
    float pad;
};

struct DeformParams {
    mat4 probe_to_index;     // pressed probe frame [mm] (x lateral, y beam, z elevation) -> label voxel index
    uint columns;
    uint rows;
    float pixel_x_mm;        // lateral pixel step [mm]
    float pixel_y_mm;        // depth pixel step [mm]
    float width_mm;          // the image's width [mm], centred on the probe
    float depth_mm;          // the image's depth [mm]
    float skin_pressure_kpa; // the probe's force over its face [kPa]
    float pulse;             // where the heart cycle is: 0 (diastole) .. 1 (systolic peak)
    float face_width_mm;     // the face's extent along the array [mm]
    float face_length_mm;    // and across it (elevation) [mm]
    float step_mm;           // the column walk's step [mm]
    uint max_steps;          // the scratch holds this many steps per column
    float tgc_db_cm_mhz;     // the attenuation the time-gain compensation assumes [dB/cm/MHz]
    float frequency_mhz;
    uint flags;              // DEFORM_PAPER_LINEAR
};

// A walk step's scratch entry as it is kept between the walks: four half floats in two words. A SIMD
// device stores and loads a word at a time per lane (llvmpipe: a loop over the lanes), and the
// walks go over the scratch five to eight times; what an entry holds (compliances, strains, a
// lumen's closure, shares, gains in dB, distances in mm) needs no more than half's 11 bits; the
// walk's "no lumen that way" distance (1e9) becomes half's largest or infinity, which the min() it
// meets takes alike. The CPU twin keeps the scratch the same way, so both round alike.
KERNEL_FN uvec2 scratch_pack(vec4 v) { return uvec2(packHalf2x16(vec2(v.x, v.y)), packHalf2x16(vec2(v.z, v.w))); }
KERNEL_FN vec4 scratch_unpack(uvec2 u)
{
    vec2 a = unpackHalf2x16(u.x), b = unpackHalf2x16(u.y);
    return vec4(a.x, a.y, b.x, b.y);
}

// The vertical stress under the corner of a uniformly loaded l x b rectangle at depth z, as a
// fraction of the load (Newmark's integration of Boussinesq's solution). A negative l or b counts
// the rectangle negatively (superposition for points outside the face).
KERNEL_FN float corner_influence(float l, float b, float z)
{
    float m = abs(l) / z, n = abs(b) / z;
    float m2 = m * m, n2 = n * n, s = m2 + n2 + 1.0f, r = sqrt(s);
    float first = 2.0f * m * n * r / (s + m2 * n2) * (s + 1.0f) / s;
    float second = atan(2.0f * m * n * r, s - m2 * n2);  // the branch past pi/2 where m n is large
    return sign(l) * sign(b) * (first + second) / (4.0f * 3.14159265f);
}

// The fraction of the skin pressure felt at depth z [mm] below lateral position x [mm] under a face
// of width w (along x) and length l (elevation), centred at x = 0.
KERNEL_FN float face_influence(float x, float z, float w, float l)
{
    float zz = max(z, 1e-3f);
    return 2.0f * (corner_influence(0.5f * w + x, 0.5f * l, zz) + corner_influence(0.5f * w - x, 0.5f * l, zz));
}

// Whether a tissue is a vessel's lumen (which may close, or widen with the pulse), not a solid.
KERNEL_FN bool is_lumen_tissue(TissueMechanics t) { return t.max_closure > 0.0f || t.pulse_strain > 0.0f; }

// The fraction of its length a lumen loses at transmitted pressure p [kPa] (negative: it widens).
KERNEL_FN float lumen_closure(TissueMechanics t, float p, float pulse)
{
    if (!is_lumen_tissue(t)) return 0.0f;
    float onset = t.collapse_onset_kpa, width = max(t.collapse_width_kpa, 1e-6f);
    return t.max_closure * smoothstep(onset, onset + width, p) - t.pulse_strain * pulse;
}

// A solid step's strain at stress level s [kPa] with compliance a = compliance x influence [1/kPa].
KERNEL_FN float solid_strain(float a, float max_strain, float s)
{
    return clamp(a * s, -max_strain, max_strain);
}

// The change [dB] a lumen step of length h [mm] that lost `closure` of itself makes to what lies below.
KERNEL_FN float closure_gain_db(float closure, float h, TissueMechanics t, float tgc_db_cm_mhz, float frequency_mhz)
{
    return -2.0f * closure * h * (tgc_db_cm_mhz - t.attenuation) * frequency_mhz / 10.0f;
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif

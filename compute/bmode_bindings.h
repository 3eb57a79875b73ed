// Bindings of the B-mode synthesis kernels (compute/bmode_scatter.comp, bmode_beam.comp,
// bmode_axial.comp, bmode_lateral.comp), shared with their CPU twin (engine/echo/bmode.cpp) and their dispatcher
// (engine/image/bmode_gpu.cpp). The model is engine/echo/bmode.hpp's; here is its arithmetic, written
// once in the subset of GLSL and C++ that kernel_shared.h makes common, so the twins compute the
// same floats in the same order.
//
// The anatomy comes in as a tissue-label volume (uint8 codes, echo::Tissue, voxelised from the
// phantom on the CPU) and per-tissue acoustic tables in BModeParams, so a changed phantom or a new
// tissue needs no shader change (up to BMODE_MAX_TISSUES codes).
//
// Four passes per batch of frames (gl_GlobalInvocationID.z / the frame index picks the frame):
//   1. scatter (per pixel): the tissue at the pixel, the complex scatterer field summed over the
//      beam's elevational planes, times the tissue's scattering strength and texture;
//   2. beam (per column, down the rows): attenuation less TGC, specular echoes at label changes,
//      the shadow of what is reflected;
//   3. axial (per pixel): the axial point-spread function down the column;
//   4. lateral (per run of 4 pixels of a row): the lateral point-spread function, the envelope
//      (magnitude) and log compression, packed 4 grey bytes and 4 label bytes to a word.
#ifndef ECHOSIM_BMODE_BINDINGS_H
#define ECHOSIM_BMODE_BINDINGS_H

#include "kernel_shared.h"
#include "slice_bindings.h"

#ifdef __cplusplus
namespace echosim::kernels {
using glm::ivec3;
}
// the twins must round alike: GLSL's `precise` forbids fusing a*b+c into one FMA, which lavapipe's
// compiler otherwise does; C++ here is built without FMA contraction (no -march)
#define BMODE_PRECISE
#else
#define BMODE_PRECISE precise
#endif

#ifdef __cplusplus
namespace echosim::kernels {
#endif

#define BMODE_SCATTER_GROUP_X 16
#define BMODE_SCATTER_GROUP_Y 4
#define BMODE_BEAM_GROUP 32
#define BMODE_AXIAL_GROUP_X 16
#define BMODE_AXIAL_GROUP_Y 4
#define BMODE_LATERAL_GROUP_X 16  // runs of 4 pixels
#define BMODE_LATERAL_GROUP_Y 4

#define BMODE_MAX_TISSUES 32
#define BMODE_MAX_PLANES 32  // elevational planes
#define BMODE_MAX_TAPS 128   // taps of the axial or the lateral point-spread function (2 radius + 1)
#define BMODE_MAX_FRAMES 32  // frames in one batch

#define BMODE_PARAMS_BINDING 0   // uniform BModeParams
#define BMODE_FRAMES_BINDING 1   // uniform BModeFrames: the batch's probe poses
#define BMODE_VOLUME_BINDING 2   // uniform texel buffer, R8_UINT: the tissue-label volume, x fastest
#define BMODE_FIELD_BINDING 3    // vec2 per pixel, buffer A: the scattered field (pass 1), then after the axial PSF (pass 3)
#define BMODE_LABELS_BINDING 4   // uint per pixel: the tissue code (pass 1)
#define BMODE_BEAM_BINDING 5     // vec2 per pixel, buffer B: the field down the beam, attenuated, with its echoes (pass 2)
#define BMODE_BEAM_TEXELS_BINDING 6   // buffer B as RG32F texels (pass 3 reads it)
#define BMODE_GREY_BINDING 7     // uint per 4 pixels of a row: grey bytes, x fastest (pass 4)
#define BMODE_LABEL_OUT_BINDING 8  // uint per 4 pixels of a row: tissue codes (pass 4)
#define BMODE_ENVELOPE_BINDING 9   // float per pixel: the envelope before log compression (pass 4, variant)
#define BMODE_FIELD_TEXELS_BINDING 10  // buffer A as RG32F texels (passes 2 and 4 read it)
#define BMODE_LABEL_TEXELS_BINDING 11  // the tissue codes as R32UI texels (passes 2 and 4 read them)
// Live frames (generative imaging: compute/bmode_live.comp replaces pass 1 for a frame of the echographic
// image, image/echo_image_gpu.hpp), in the same set as the passes above:
// (one block with the slice's parameters in it: with them in a block of their own, lavapipe, Mesa
// 22.3, crashed running this kernel once it fetched from a texel buffer or an image)
#define BMODE_LIVE_FRAME_BINDING 12   // uniform BModeLiveFrame: the pressed probe's image frame and the frame's slice parameters
#define BMODE_LIVE_MAP_BINDING 13     // texel buffer, RG32F: the deform map (source y [mm], gain [dB])
// and the case's tissue codes at BMODE_VOLUME_BINDING, as a sweep's label volume: a texel buffer,
// x fastest, on the echographic volume's grid
// Reads go through texel views, writes to storage: on a CPU device (lavapipe) a texel fetch is one
// vector gather, a storage buffer's load a loop over the lanes; so no pass reads what it writes.

// the lateral pass's variant (specialization constant 0): also write the envelope
#define BMODE_WITH_ENVELOPE 1u

// The synthesis's fixed parameters (std140: every array of vec4, scalars in fours).
struct BModeParams {
    uint columns, rows, frames, row_words;  // image size; frames in this batch; words per packed row
    uint planes, axial_radius, lateral_radius, tissue_count;
    uint volume_size_x, volume_size_y, volume_size_z, texture;  // texture: muscle fibres and fat septa on (1) or off (0)
    float pixel_mm, width_mm, lattice_inverse, specular;  // lattice_inverse: 1 / scatterer lattice [1/mm]
    float reference, gain_db, dynamic_range_db, pad1;     // log compression (log_compress_bindings.h)
    vec4 volume_origin;     // world position of the label volume's voxel (0, 0, 0) centre [mm]
    vec4 volume_inverse[3]; // rows of world -> continuous voxel index (the inverse of its directions)
    vec4 muscle_cells;      // 1 / cell size [1/mm] of the muscle's fibre texture, world x, y, z
    vec4 fat_cells;         // the same for the fat's septa
    vec4 scatter[BMODE_MAX_TISSUES / 4];    // scattering strength by tissue
    vec4 step[BMODE_MAX_TISSUES / 4];       // round-trip amplitude factor over one pixel: attenuation less TGC
    vec4 reflect[BMODE_MAX_TISSUES * BMODE_MAX_TISSUES / 4];  // reflection coefficient, [above * 16 + below]
    vec4 pass[BMODE_MAX_TISSUES * BMODE_MAX_TISSUES / 4];     // 1 - reflect^2: what goes on below
    vec4 elevation[BMODE_MAX_PLANES];  // (offset along the probe's z [mm], weight, 0, 0) per plane
    vec4 axial[BMODE_MAX_TAPS / 4];    // axial PSF taps, 2 axial_radius + 1
    vec4 lateral[BMODE_MAX_TAPS / 4];  // lateral PSF taps, 2 lateral_radius + 1
};

// A probe pose as the kernels take it: the image's origin (the face's centre) and axes, world mm.
struct BModePose {
    vec4 origin, x, y, z;
};
struct BModeFrames {
    BModePose frame[BMODE_MAX_FRAMES];
};

// A live frame: the pressed probe's image frame (world mm), where the tissue's rest state is looked
// up: each pixel's source (x, source y) in it, the deform map's (deform_bindings.h) source depth.
struct BModeLiveFrame {
    BModePose pose;
    SliceParams slice;  // the frame's (slice_bindings.h): the plane, the deform map's geometry, the pressed probe -> label voxel
};

// The shared functions read the parameters as `k`: a reference argument in C++ (BMODE_K), the
// uniform block itself in GLSL (declared here, so every pass reads it alike).
#ifdef __cplusplus
#define BMODE_K , const BModeParams& k
#define BMODE_INOUT(T) T&
#define BMODE_ARG , k
#define BMODE_K_ONLY const BModeParams& k
#else
layout(std140, binding = BMODE_PARAMS_BINDING) uniform Params { BModeParams k; };
#define BMODE_K
#define BMODE_INOUT(T) inout T
#define BMODE_K_ONLY
#define BMODE_ARG
#endif

// element k of a vec4-packed table
KERNEL_FN float bmode_at(vec4 v, uint i) { return v[int(i & 3u)]; }

// A 32-bit integer finaliser (C. Wellons' "lowbias32": every input bit flips each output bit with
// probability close to 1/2), cheaper on a CPU device than 64-bit arithmetic.
KERNEL_FN uint bmode_mix(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// A hash of the lattice cell that holds world point p (cells of 1 / inverse mm along world x, y, z):
// fixed in the body, so every frame that sees a cell sees the same scatterer.
KERNEL_FN uint bmode_cell_hash(vec3 p, vec3 inverse, uint salt)
{
    BMODE_PRECISE vec3 q = p * inverse;
    const ivec3 c = ivec3(floor(q));
    return bmode_mix(uint(c.x) + bmode_mix(uint(c.y) + bmode_mix(uint(c.z) + salt)));
}

// A unit scatterer: real and imaginary parts uniform on [-sqrt 3, sqrt 3) (each of variance 1, as a
// complex Gaussian's: the PSF sums hundreds of them, so the field is Gaussian all the same).
KERNEL_FN vec2 bmode_scatterer(uint h)
{
    return (vec2(float(h & 0xffffu), float(h >> 16u)) - vec2(32767.5f)) * (1.7320508f / 32768.0f);
}

// The world position of pixel (column c, row r) of the frame.
KERNEL_FN vec3 bmode_pixel_world(BModePose f, uint c, uint r, float pixel_mm, float width_mm)
{
    const float x = pixel_x(c, pixel_mm, width_mm), y = pixel_y(r, pixel_mm);
    BMODE_PRECISE vec3 along_x = vec3(f.x) * x;
    BMODE_PRECISE vec3 along_y = vec3(f.y) * y;
    BMODE_PRECISE vec3 p = vec3(f.origin) + along_x;
    p = p + along_y;
    return p;
}

// Where the tissue a live frame shows at (x, source_y) of its pressed image frame rests, world mm:
// the same lattice the sweeps hash, so the speckle the trainee presses is the recorded one's, and it
// moves with the tissue (its cell is the tissue's rest position's, wherever the pixel now shows it).
KERNEL_FN vec3 bmode_live_world(BModePose f, float x, float source_y)
{
    BMODE_PRECISE vec3 along_x = vec3(f.x) * x;
    BMODE_PRECISE vec3 along_y = vec3(f.y) * source_y;
    BMODE_PRECISE vec3 p = vec3(f.origin) + along_x;
    p = p + along_y;
    return p;
}

// The label volume's voxel nearest to p, as an index into it (x fastest), or -1 outside it.
KERNEL_FN int bmode_voxel(vec3 p BMODE_K)
{
    // the dot products written out: `precise` binds the products and sums a statement spells, not
    // a built-in's inside (an NVIDIA GPU fused dot()'s into FMAs, so pixels lying on a voxel's
    // boundary, as every other 0.1 mm pixel does on a 0.2 mm label grid, rounded to the other voxel
    // than the CPU twin's)
    BMODE_PRECISE vec3 d = p - vec3(k.volume_origin);
    const vec3 ri = vec3(k.volume_inverse[0]), rj = vec3(k.volume_inverse[1]), rl = vec3(k.volume_inverse[2]);
    BMODE_PRECISE float i = ri.x * d.x + ri.y * d.y + ri.z * d.z;
    BMODE_PRECISE float j = rj.x * d.x + rj.y * d.y + rj.z * d.z;
    BMODE_PRECISE float l = rl.x * d.x + rl.y * d.y + rl.z * d.z;
    const float fi = floor(i + 0.5f), fj = floor(j + 0.5f), fl = floor(l + 0.5f);
    if (fi < 0.0f || fj < 0.0f || fl < 0.0f || fi >= float(k.volume_size_x) || fj >= float(k.volume_size_y) || fl >= float(k.volume_size_z))
        return -1;
    return int(fi) + int(k.volume_size_x) * (int(fj) + int(k.volume_size_y) * int(fl));
}

// The live frames' scatterers (bmode_live.comp): a continuous field of the body's position, one
// scatterer at each corner of the 0.1 mm lattice's cells interpolated trilinearly between them, and
// scaled back to unit variance (a blend of independent scatterers is quieter than each by the sum
// of its squared weights). Point-sampled as the sweeps' is, the field jumps as a pixel's tissue
// crosses a cell's edge: a probe sliding 0.01 mm a frame changed the image 14 grey levels a frame,
// and under a press of 1 mm the pressed image's blocks found in the image at rest correlated 0.25
// to 0.8; interpolated, a tissue moved a fraction of a cell moves its speckle with it (Storve &
// Torp's sub-sample motion without flicker). A corner's scatterer is one finaliser over the sum of
// its coordinates' odd multiples (eight finalisers a cell, where the sweeps' nested hash would take
// fourteen: the live image's largest cost).
KERNEL_FN vec2 bmode_smooth_scatterer(vec3 p, vec3 inverse, uint salt)
{
    BMODE_PRECISE vec3 q = p * inverse;
    const vec3 base = floor(q);
    const ivec3 c = ivec3(base);
    BMODE_PRECISE vec3 f = q - base;
    const uint kx = 0x9e3779b1u, ky = 0x85ebca77u, kz = 0xc2b2ae3du;
    const uint x0 = uint(c.x) * kx + salt, x1 = x0 + kx;
    const uint yz00 = uint(c.y) * ky + uint(c.z) * kz, yz10 = yz00 + ky, yz01 = yz00 + kz, yz11 = yz10 + kz;
    BMODE_PRECISE vec2 a00 = mix(bmode_scatterer(bmode_mix(x0 + yz00)), bmode_scatterer(bmode_mix(x1 + yz00)), f.x);
    BMODE_PRECISE vec2 a10 = mix(bmode_scatterer(bmode_mix(x0 + yz10)), bmode_scatterer(bmode_mix(x1 + yz10)), f.x);
    BMODE_PRECISE vec2 a01 = mix(bmode_scatterer(bmode_mix(x0 + yz01)), bmode_scatterer(bmode_mix(x1 + yz01)), f.x);
    BMODE_PRECISE vec2 a11 = mix(bmode_scatterer(bmode_mix(x0 + yz11)), bmode_scatterer(bmode_mix(x1 + yz11)), f.x);
    BMODE_PRECISE vec2 b0 = mix(a00, a10, f.y);
    BMODE_PRECISE vec2 b1 = mix(a01, a11, f.y);
    BMODE_PRECISE vec2 v = mix(b0, b1, f.z);
    BMODE_PRECISE vec3 g = vec3(1.0f) - f;
    BMODE_PRECISE vec3 w = g * g + f * f;  // each axis's blend's variance
    BMODE_PRECISE float variance = w.x * w.y * w.z;
    return v * (1.0f / sqrt(variance));
}

// The complex scatterer field at p summed over the beam's elevational planes (along the probe's
// z), each plane one lattice step from the next and weighted by the beam's profile: the field
// point-sampled for a sweep, interpolated for a live frame (`live_field`, bmode_smooth_scatterer).
KERNEL_FN vec2 bmode_elevation_sum(vec3 p, vec3 z, bool live_field BMODE_K)
{
    BMODE_PRECISE vec2 sum = vec2(0.0f);
    const vec3 inverse = vec3(k.lattice_inverse);
    for (uint e = 0u; e < k.planes; ++e) {
        const vec4 plane = k.elevation[e];
        BMODE_PRECISE vec3 off = z * plane.x;
        BMODE_PRECISE vec3 q = p + off;
        BMODE_PRECISE vec2 s = (live_field ? bmode_smooth_scatterer(q, inverse, 17u) : bmode_scatterer(bmode_cell_hash(q, inverse, 17u))) * plane.y;
        sum = sum + s;
    }
    return sum;
}

// Tissue texture at p: muscle fibres run along the limb (world z: slow along it, quick across); fat
// carries thin bright septa. Tissue codes as echo::Tissue (fat 2, muscle 4).
KERNEL_FN float bmode_texture(uint tissue, vec3 p BMODE_K)
{
    if (tissue == 4u) return 0.55f + 0.9f * (float(bmode_cell_hash(p, vec3(k.muscle_cells), 3u) >> 8u) * (1.0f / 16777216.0f));
    if (tissue == 2u) return (float(bmode_cell_hash(p, vec3(k.fat_cells), 5u) >> 8u) * (1.0f / 16777216.0f)) > 0.88f ? 3.0f : 1.0f;
    return 1.0f;
}

// Pass 1 for one pixel: the scattered field at p (world) of a pixel of `tissue` (`live_field`: a live
// frame's, bmode_elevation_sum).
KERNEL_FN vec2 bmode_scattered(vec3 p, vec3 z, uint tissue, bool live_field BMODE_K)
{
    float strength = bmode_at(k.scatter[tissue >> 2u], tissue);
    if (k.texture != 0u) strength *= bmode_texture(tissue, p BMODE_ARG);
    BMODE_PRECISE vec2 f = bmode_elevation_sum(p, z, live_field BMODE_ARG) * strength;
    return f;
}

// Live frames (bmode_live.comp, echo::synthesize_live): where a vein's walls met under the probe,
// the deform map skips its lumen from one row to the next. The pixel there shows the lumen's last
// trace, so the beam pass puts the wall's echo on either side of it, one pixel apart, which the
// pulse's length makes one bright line: the two walls' echoes become one, as a sonographer sees a
// vein close (without it the closed vein vanished into the speckle). `skipped_mm`: how much rest
// depth the map skipped from the row above to this one; `middle`: the tissue halfway across it.
// A closing lumen only (vein, great saphenous vein: echo::Tissue's codes); compressed fat, the most
// squeezed solid, skips a third of a millimetre a row.
#define BMODE_COAPTED_SKIP_MM 1.0f
#define BMODE_VEIN_LUMEN 7u
#define BMODE_SAPHENOUS_LUMEN 10u
KERNEL_FN uint bmode_coapted(uint t, uint middle, float skipped_mm)
{
    return skipped_mm > BMODE_COAPTED_SKIP_MM && (middle == BMODE_VEIN_LUMEN || middle == BMODE_SAPHENOUS_LUMEN) ? middle : t;
}

// Pass 2, one pixel down a column: the field of a pixel of tissue `t` (the pixel above of `above`;
// `first`: the top row) scaled by the amplitude `transmitted` that reaches it and comes back, plus
// the specular echo where the tissue changes; then `transmitted` on past it: less what the
// interface reflects, times the round trip through the pixel less the time-gain compensation.
KERNEL_FN vec2 bmode_beam_step(vec2 f, uint above, uint t, bool first, BMODE_INOUT(float) transmitted BMODE_K)
{
    BMODE_PRECISE vec2 out_f = f * transmitted;
    if (!first && above != t) {
        const uint pair = above * uint(BMODE_MAX_TISSUES) + t;
        BMODE_PRECISE float echo_amplitude = k.specular * bmode_at(k.reflect[pair >> 2u], pair);
        echo_amplitude = echo_amplitude * transmitted;
        out_f.x = out_f.x + echo_amplitude;  // a real echo: in phase with the pulse
        transmitted = transmitted * bmode_at(k.pass[pair >> 2u], pair);
    }
    transmitted = transmitted * bmode_at(k.step[t >> 2u], t);
    return out_f;
}

// tap i of the axial / lateral point-spread function
KERNEL_FN float bmode_axial_tap(uint i BMODE_K) { return bmode_at(k.axial[i >> 2u], i); }
KERNEL_FN float bmode_lateral_tap(uint i BMODE_K) { return bmode_at(k.lateral[i >> 2u], i); }

// The envelope: the magnitude of the field after the point-spread function.
KERNEL_FN float bmode_envelope(vec2 f)
{
    BMODE_PRECISE float m = f.x * f.x;
    BMODE_PRECISE float n = f.y * f.y;
    m = m + n;
    return sqrt(m);
}

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif

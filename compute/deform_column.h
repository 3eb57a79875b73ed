// The deform kernel's body, one image column (the model: deform_bindings.h). Written once in the
// common subset of GLSL and C++ (kernel_shared.h): compute/deform.comp includes it at file scope,
// and its CPU twin (engine/echo/deform_cpu.cpp) inside a class body, so both run these very lines.
// The includer first defines what the body reads and writes:
//   uint deform_label(vec3 index)          the tissue code at a continuous label-voxel index
//   TissueMechanics deform_tissue(uint code)
//   vec2 deform_profile(uint column)       (skin_y, skin_shift) [mm]
//   vec4 scratch_load(uint column, uint step) / void scratch_store(uint column, uint step, vec4 v)
//                                          (where a step's entry lies is the includer's: the GPU
//                                          interleaves the columns, the CPU keeps each together)
//   void map_store(uint pixel, vec2 v)     (source y [mm], gain [dB]) of pixel = row * columns + column

void deform_column(uint c, DeformParams p)
{
    float x = pixel_x(c, p.pixel_x_mm, p.width_mm);
    vec2 profile = deform_profile(c);
    float skin_y = profile.x, shift = profile.y;
    float h = p.step_mm;
    bool linear = (p.flags & DEFORM_PAPER_LINEAR) != 0u;
    uint steps = uint(clamp(ceil((p.depth_mm - skin_y) / h), 0.0f, float(p.max_steps)));

    // 1. down the column from the skin: each step's tissue, its compliance under the stress that
    //    reaches it, and how much of it a lumen loses to the pressure there. A scratch entry is
    //    (a, e, 0, 1) for a solid step (compliance x influence [1/kPa], largest strain, and its
    //    share of the inflow below) and (0, 0, closure, gain [dB]) for a lumen step.
    float closed = 0.0f;  // [mm]
    bool closing = false;
    // 2. (in the same walk) the solids compress under the probe's pressure as it reaches them (the
    //    paper's linear deformation has no pressure law: its column takes the shift alone)
    float stress = linear ? 0.0f : p.skin_pressure_kpa;
    float pressed = 0.0f;  // [mm]
    for (uint k = 0u; k < steps; ++k) {
        float depth = (float(k) + 0.5f) * h;
        vec4 at = p.probe_to_index * vec4(x, skin_y + depth, 0.0f, 1.0f);
        TissueMechanics t = deform_tissue(linear ? 0u : deform_label(vec3(at)));
        float influence = linear ? 1.0f : face_influence(x, depth, p.face_width_mm, p.face_length_mm);
        float closure = lumen_closure(t, p.skin_pressure_kpa * influence, p.pulse);
        closed += closure * h;
        closing = closing || closure > 0.0f;
        vec4 w = closure != 0.0f ? vec4(0.0f, 0.0f, closure, closure_gain_db(closure, h, t, p.tgc_db_cm_mhz, p.frequency_mhz))
                                 : vec4(t.compliance * influence, t.max_strain, 0.0f, 1.0f);
        scratch_store(c, k, w);
        if (w.z == 0.0f) pressed += solid_strain(w.x, w.y, stress) * h;
    }

    // 3. what the pressure and the lumens leave of the skin's shift (from the simulated tissue) is
    //    taken up by the solids in series. Where a lumen closes, that remainder is the tissue around
    //    it flowing into the space (a column cannot show the flow from the sides otherwise): only
    //    the solid steps near a closing lumen take it, their share halving every DEFORM_INFLOW_MM.
    float residual = shift - closed - pressed;
    if (closing) {
        float since = 1e9f;  // [mm] from the last closing step above
        for (uint k = 0u; k < steps; ++k) {
            vec4 w = scratch_load(c, k);
            since = w.z > 0.0f ? 0.0f : since + h;
            if (w.z == 0.0f) scratch_store(c, k, vec4(w.x, w.y, 0.0f, since));
        }
        float until = 1e9f;  // [mm] to the next closing step below
        for (uint k = steps; k > 0u; --k) {
            vec4 w = scratch_load(c, k - 1u);
            until = w.z > 0.0f ? 0.0f : until + h;
            if (w.z == 0.0f) scratch_store(c, k - 1u, vec4(w.x, w.y, 0.0f, exp2(-min(w.w, until) / DEFORM_INFLOW_MM)));
        }
    }
    //    The remainder's level sigma: sum_k h min(g_k sigma, room_k) = |residual|, with g_k = a_k x
    //    share_k and room_k what step k's largest strain leaves. From sigma = 0, each pass solves the
    //    linear law with the steps the last sigma filled held full; sigma only grows towards the
    //    answer, and reaches it once the filled set stops changing.
    float dir = sign(residual);
    float sigma = 0.0f;
    for (int pass = 0; pass < 16; ++pass) {
        float free_sum = 0.0f, full = 0.0f;
        for (uint k = 0u; k < steps; ++k) {
            vec4 w = scratch_load(c, k);
            if (w.z != 0.0f) continue;
            float g = w.x * w.w, room = w.y - dir * solid_strain(w.x, w.y, stress);
            if (g * sigma >= room) full += room * h;
            else free_sum += g * h;
        }
        if (free_sum <= 0.0f) break;  // every step rigid or full: the column cannot take more
        float next = (abs(residual) - full) / free_sum;
        if (next <= sigma) break;
        sigma = next;
    }

    // 4. where each step lies now, and which pixels it covers: every pixel maps back to the depth it
    //    came from (inverse warp: no holes), with the gain the closed lumens above it make
    float shortened = 0.0f, gain = 0.0f;
    uint r = 0u;
    while (r < p.rows && pixel_y(r, p.pixel_y_mm) < skin_y + shift) {  // the gel above the skin moves with it
        map_store(r * p.columns + c, vec2(pixel_y(r, p.pixel_y_mm) - shift, 0.0f));
        ++r;
    }
    for (uint k = 0u; k < steps && r < p.rows; ++k) {
        vec4 w = scratch_load(c, k);
        float pressure_strain = solid_strain(w.x, w.y, stress);
        float strain = w.z != 0.0f ? w.z : pressure_strain + dir * min(w.x * w.w * sigma, w.y - dir * pressure_strain);
        float top = skin_y + float(k) * h + shift - shortened;
        float length = h * (1.0f - strain);
        while (r < p.rows && pixel_y(r, p.pixel_y_mm) < top + length) {
            float f = length > 0.0f ? clamp((pixel_y(r, p.pixel_y_mm) - top) / length, 0.0f, 1.0f) : 0.0f;
            map_store(r * p.columns + c, vec2(skin_y + (float(k) + f) * h, gain));
            ++r;
        }
        shortened += strain * h;
        gain += w.z != 0.0f ? w.w : 0.0f;
    }
    float rest = shift - shortened;  // what the column could not take up moves the tissue below
    while (r < p.rows) {
        map_store(r * p.columns + c, vec2(pixel_y(r, p.pixel_y_mm) - rest, gain));
        ++r;
    }
}

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
//   float moved_load(uint column, uint boundary) / void moved_store(uint column, uint boundary, float v)
//                                          how far a step boundary moved down the beam [mm]
//   vec2 walls_load(uint column, uint boundary) / void walls_store(uint column, uint boundary, vec2 v)
//                                          its distances [mm] to what fixes it (walk 5), kept as
//                                          half floats (packHalf2x16) by both includers
//                                          (both max_steps + 1 boundaries a column)
//   float spread_load(uint column, uint boundary) / void spread_store(uint column, uint boundary, float v)
//                                          the displacement spread sideways (deform_column_spread)
//   bool spread_loaded()                   whether the spread pass ran, or the map spreads in its walk
//   void map_store(uint pixel, vec2 v)     (source y [mm], gain [dB]) of pixel = row * columns + column
// and runs deform_column_solve for every column, then (once all are done: the spread reads the
// neighbours' displacements) deform_column_map for every column, with or without first
// deform_column_spread for every column's boundaries 1 to its steps (spread_loaded: the same
// figures either way, each a pure function of the solve's).

// Whether a scratch entry is a lumen's (a solid's compliance is never negative).
bool is_lumen(vec4 w) { return w.x < 0.0f; }

// Whether a scratch entry's step is rigid (bone, and what lies below it), so the sideways spread
// must not move it. (A lumen that stays open, an artery, keeps its shape otherwise: the map pass
// carries it whole, deform_column_map.)
bool is_rigid(vec4 w) { return !is_lumen(w) && w.y == 0.0f; }

// What a solid step of weight g (compliance, or share) and largest strain `largest` takes of one
// of the column's remainders [strain] (deform_column_solve, walk 4): at the remainder's `level`,
// signed by its direction, up to the room its largest strain leaves that way; and past that room,
// a share of the remainder's `overflow` (signed too) in proportion to its largest strain (the
// softer, the more) and to what is left of its length that way, so it never reaches nothing. Only
// a column whose steps are all full overflows (remainder_level); a rigid step (bone) takes none.
float remainder_strain(float g, float largest, float level, float overflow, float room)
{
    return sign(level) * min(g * abs(level), max(room, 0.0f)) + largest * overflow * (room + 1.0f - largest);
}

// A solid step's strain once the column's two remainders are taken up: `solved` = (level, overflow)
// of the first (by compliance, w.x) and of the second (by share, w.w), from `stage` 0 (the
// pressure's strain alone) to 2 (both).
float solid_strain_after(vec4 w, float stress, vec4 solved, uint stage)
{
    float strain = solid_strain(w.x, w.y, stress);
    if (stage > 0u) strain += remainder_strain(w.x, w.y, solved.x, solved.y, w.y - sign(solved.x + solved.y) * strain);
    if (stage > 1u) strain += remainder_strain(w.w, w.y, solved.z, solved.w, w.y - sign(solved.z + solved.w) * strain);
    return strain;
}

// How stage `stage`'s remainder `amount` [mm] is taken up: the level sigma at which sum_k h min(g_k
// sigma, room_k) = |amount|, g_k the step's weight (compliance, or share), room_k what its largest
// strain leaves after the stages before. From sigma = 0, each pass solves the linear law with the
// steps the last sigma filled held full; sigma only grows towards the answer, and reaches it once
// the filled set stops changing. A pass also finds the lowest level at which a step it left free
// would fill: a new sigma below it fills none, so the set cannot change and no pass is needed to
// see that (each pass is a walk over the column: the common case, where no step fills, takes one).
// When the steps' rooms together cannot take the remainder (a deep press over a column of little
// soft tissue: the sum of the largest strains falls short of the skin's shift), every step is
// full, and the rest, the overflow, is shared by the steps that are not rigid past their largest
// strains (remainder_strain), none losing more than DEFORM_OVERFLOW_MAX of what is left of it: in
// truth that tissue flows out to the sides, which a column cannot show, while the bone and the
// deep end stay where they are (what no step takes moves them). Returns (level, overflow), both
// signed by the remainder's direction.
vec2 remainder_level(uint c, uint steps, float h, float stress, float amount, vec4 solved, uint stage)
{
    float dir = sign(amount), sigma = 0.0f;
    for (int pass = 0; pass < 16; ++pass) {
        float free_sum = 0.0f, full = 0.0f, fills_at = 3.0e38f;
        float capacity = 0.0f, last_fill = 0.0f, weights = 0.0f, softest = 0.0f;  // (first pass) for an overflow
        for (uint k = 0u; k < steps; ++k) {
            vec4 w = scratch_load(c, k);
            if (is_lumen(w)) continue;
            float g = stage == 0u ? w.x : w.w, strain = solid_strain_after(w, stress, solved, stage);
            float room = max(w.y - dir * strain, 0.0f);
            if (pass == 0) {  // what an overflow is shared by (remainder_strain)
                if (g > 0.0f) {
                    capacity += room * h;
                    last_fill = max(last_fill, room / g);
                }
                weights += w.y * (1.0f - dir * strain) * h;  // the largest strain, and what is left of the length that way
                softest = max(softest, w.y);
            }
            if (g * sigma >= room) {
                full += room * h;
            } else {
                free_sum += g * h;
                if (g > 0.0f) fills_at = min(fills_at, room / g);
            }
        }
        if (pass == 0 && abs(amount) >= capacity && weights > 0.0f)
            return vec2(dir * last_fill, dir * min((abs(amount) - capacity) / weights, DEFORM_OVERFLOW_MAX / softest));
        if (free_sum <= 0.0f) break;  // every step rigid or full: the column cannot take more
        float next = (abs(amount) - full) / free_sum;
        if (next <= sigma) break;
        sigma = next;
        // within a part in 10^5 of filling counts as filling: the next pass decides it exactly
        if (next < fills_at * 0.99999f) break;
    }
    return vec2(dir * sigma, 0.0f);
}

// The steps of a column whose skin lies at skin_y: from the skin to the image's depth, as many as the
// scratch holds. Both passes walk the same ones.
uint deform_steps(float skin_y, DeformParams p) { return uint(clamp(ceil((p.depth_mm - skin_y) / p.step_mm), 0.0f, float(p.max_steps))); }

// The first pass, one column on its own: its steps' tissues, strains and displacements.
void deform_column_solve(uint c, DeformParams p)
{
    float x = pixel_x(c, p.pixel_x_mm, p.width_mm);
    vec2 profile = deform_profile(c);
    float skin_y = profile.x, shift = profile.y;
    float h = p.step_mm;
    bool linear = (p.flags & DEFORM_PAPER_LINEAR) != 0u;
    uint steps = deform_steps(skin_y, p);

    // 1. down the column from the skin: each step's tissue, its compliance under the stress that
    //    reaches it, and how much of it a lumen loses to the pressure there. A scratch entry is
    //    (a, e, 0, 0) for a solid step (compliance x influence [1/kPa], largest strain; walk 4 puts
    //    its share of the lumens' change last) and (-1, 0, closure, gain [dB]) for a lumen step,
    //    closing or not (is_lumen).
    float closed = 0.0f;  // [mm]
    bool changing = false;  // whether a lumen closes or widens
    // 2. (in the same walk) the solids compress under the probe's pressure as it reaches them (the
    //    paper's linear deformation has no pressure law: its column takes the shift alone)
    float stress = linear ? 0.0f : p.skin_pressure_kpa;
    float pressed = 0.0f;  // [mm]
    // 3. (in the same walk) the first rigid step (bone) anchors the column, as the tissue model's
    //    springs are anchored there: what lies below it neither moves nor feels the probe, so the
    //    tissue above takes up the whole shift and the bone stays where it is
    bool anchored = false;
    vec2 gained = vec2(0.0f);  // the first and last lumen steps with a gain, plus one ((0, 0): none), for walk 6
    for (uint k = 0u; k < steps; ++k) {
        float depth = (float(k) + 0.5f) * h;
        // the tissue at the step's quarters: a lumen in either makes it a lumen step, so where
        // walls meet no more than a quarter step of blood on either side is left to show
        vec4 upper = p.probe_to_index * vec4(x, skin_y + depth - 0.25f * h, 0.0f, 1.0f);
        vec4 lower = p.probe_to_index * vec4(x, skin_y + depth + 0.25f * h, 0.0f, 1.0f);
        TissueMechanics t = deform_tissue(linear ? 0u : deform_label(vec3(upper)));
        TissueMechanics t_lower = deform_tissue(linear ? 0u : deform_label(vec3(lower)));
        t = is_lumen_tissue(t) || !is_lumen_tissue(t_lower) ? t : t_lower;
        anchored = anchored || (!is_lumen_tissue(t) && t.max_strain == 0.0f);
        // the stress reaches the step where it lies now, below the pressed face, not where it lay
        // at rest: what the steps above lost to the pressure and their lumens brought it nearer
        // (a vein under 38 mm of fat, the probe 20 mm in, feels the stress of half its depth)
        float now = max(depth - pressed - closed, 0.5f * h);
        float influence = linear ? 1.0f : face_influence(x, now, p.face_width_mm, p.face_length_mm);
        float closure = anchored ? 0.0f : lumen_closure(t, p.skin_pressure_kpa * influence, p.pulse);
        closed += closure * h;
        changing = changing || closure != 0.0f;
        vec4 w = anchored ? vec4(0.0f)
               : is_lumen_tissue(t) ? vec4(-1.0f, 0.0f, closure, closure_gain_db(closure, h, t, p.tgc_db_cm_mhz, p.frequency_mhz))
                                    : vec4(t.compliance * influence, t.max_strain, 0.0f, 0.0f);
        scratch_store(c, k, w);
        if (!is_lumen(w)) pressed += solid_strain(w.x, w.y, stress) * h;
        if (is_lumen(w) && w.w != 0.0f) gained = vec2(gained.x == 0.0f ? float(k + 1u) : gained.x, float(k + 1u));
    }

    // 4. the column's two remainders. First, what the pressure leaves of the skin's shift (from
    //    the simulated tissue), taken up by the solids in series by their compliances, as though no
    //    lumen changed. Then what the lumens lose (or gain) of their length: the tissue around
    //    them sinks and rises into the space, stretching the steps near it (the flow from the
    //    sides, which a column cannot show), each step's share halving every inflow_mm from the
    //    nearest lumen that changes, above and below alike, whatever the tissue.
    vec4 solved = vec4(0.0f);
    solved = vec4(remainder_level(c, steps, h, stress, shift - pressed, solved, 0u), 0.0f, 0.0f);
    if (changing) {
        float inflow_mm = max(DEFORM_INFLOW_MM, DEFORM_INFLOW_PER_MM * abs(closed));
        float since = 1e9f;  // [mm] from the last changing lumen step above
        for (uint k = 0u; k < steps; ++k) {
            vec4 w = scratch_load(c, k);
            since = w.z != 0.0f ? 0.0f : since + h;
            if (!is_lumen(w)) scratch_store(c, k, vec4(w.x, w.y, 0.0f, since));
        }
        float until = 1e9f;  // [mm] to the next changing lumen step below
        for (uint k = steps; k > 0u; --k) {
            vec4 w = scratch_load(c, k - 1u);
            until = w.z != 0.0f ? 0.0f : until + h;
            if (!is_lumen(w)) scratch_store(c, k - 1u, vec4(w.x, w.y, 0.0f, exp2(-min(w.w, until) / inflow_mm)));
        }
        solved = vec4(solved.x, solved.y, remainder_level(c, steps, h, stress, -closed, solved, 1u));
    }

    // 5. each step boundary's displacement down the beam [mm] and distances [mm] to the column's
    //    nearest lumen whose walls (nearly) meet and to its nearest rigid step
    //    (moved_store, walls_store; past the column's last step, the last's), for the second pass
    float moved = shift;
    vec2 since = vec2(1e9f);  // [mm] from the nearest above (meeting lumen, rigid step)
    for (uint k = 0u; k < steps; ++k) {
        vec4 w = scratch_load(c, k);
        moved_store(c, k, moved);
        walls_store(c, k, since);
        float strain = is_lumen(w) ? w.z : solid_strain_after(w, stress, solved, 2u);
        moved -= strain * h;
        since = vec2(w.z >= DEFORM_MEETING ? 0.0f : since.x + h, is_rigid(w) ? 0.0f : since.y + h);
    }
    for (uint k = steps; k <= p.max_steps; ++k) {
        moved_store(c, k, moved);
        walls_store(c, k, since);
    }
    vec2 until = vec2(1e9f);  // [mm] to the nearest below
    for (uint k = steps; k > 0u; --k) {
        vec4 w = scratch_load(c, k - 1u);
        until = vec2(w.z >= DEFORM_MEETING ? 0.0f : until.x + h, is_rigid(w) ? 0.0f : until.y + h);
        walls_store(c, k - 1u, min(walls_load(c, k - 1u), until));
    }

    // 6. where the column's lumens make a gain (walk 1), for the second pass's gain across the
    //    beam (deform_gain_band), in the skin boundary's wall distances: nothing reads those after
    //    this pass (the spread starts below the skin)
    walls_store(c, 0u, gained);
}

// What the second pass needs to blend the gain of column c across the beam: the sound that crossed
// a lumen before it closed spread sideways with the beam, so the posterior enhancement the recorded
// volume holds under a vein fades out over its edges, and so must what its closing takes away (a
// column's own gain cut it off at the lumen's last column: a line down the image from each end of
// the closed vein). A Gaussian of DEFORM_GAIN_BLUR_MM, read at two columns a side about a standard
// deviation apart (the stride), so it reaches as far at any column pitch.
struct GainBand {
    uvec4 at;      // the four neighbours read: two strides left, one left, one right, two right
    uvec4 steps;   // their steps (0: outside the image)
    vec4 weight;   // their weights (0: outside the image; the column's own is 1)
    uvec2 steps_with_gain;  // the first and last steps where any of the five has a lumen with a gain ((0, 0): none), plus one
};

GainBand deform_gain_band(uint c, DeformParams p)
{
    GainBand b;
    uint stride = uint(max(floor(DEFORM_GAIN_BLUR_MM / p.pixel_x_mm + 0.5f), 1.0f));
    float d = float(stride) * p.pixel_x_mm / DEFORM_GAIN_BLUR_MM;
    float one = exp2(-0.7213475f * d * d), two = exp2(-0.7213475f * 4.0f * d * d);  // exp(-d^2 / 2) at d and 2d
    b.at = uvec4(c - min(c, 2u * stride), c - min(c, stride), c + stride, c + 2u * stride);
    b.weight = vec4(c >= 2u * stride ? two : 0.0f, c >= stride ? one : 0.0f, c + stride < p.columns ? one : 0.0f,
                    c + 2u * stride < p.columns ? two : 0.0f);
    uvec2 band = uvec2(walls_load(c, 0u));  // deform_column_solve, walk 6
    b.steps = uvec4(0u);
    for (uint i = 0u; i < 4u; ++i) {
        if (b.weight[i] == 0.0f) continue;
        b.steps[i] = deform_steps(deform_profile(b.at[i]).x, p);
        uvec2 theirs = uvec2(walls_load(b.at[i], 0u));
        if (theirs.x > 0u) band = uvec2(band.x == 0u ? theirs.x : min(band.x, theirs.x), max(band.y, theirs.y));
    }
    b.steps_with_gain = band;
    return b;
}

// The neighbours' gains [dB] through step k (deform_column_map keeps the sums: the gains above a
// step are the sums before it), added to `sums`.
vec4 deform_gain_step(GainBand b, uint k, vec4 sums)
{
    for (uint i = 0u; i < 4u; ++i) {
        if (k >= b.steps[i]) continue;  // (outside the image, or past the column's last step)
        vec4 w = scratch_load(b.at[i], k);
        if (is_lumen(w)) sums[i] += w.w;
    }
    return sums;
}

// How far step boundary k of column c moved [mm], spread sideways: a lumen that closes drags the
// tissue around it along, over a width that grows with the distance from it (as a load spreads in
// an elastic solid), so the sinking above a closed vein fades out to the sides instead of stopping
// at its edge. What fixes a boundary's place takes no spread: the skin (which lies on the probe),
// the deep end, a closing lumen's wall and bone, so the spread's standard deviation is
// DEFORM_SPREAD times the distance to the nearest of them, up to DEFORM_SPREAD_MAX_MM. A lumen that
// closes (DEFORM_MEETING) counts in its own columns only: its walls must meet, and its neighbours
// are what the spread drags along; bone counts from the columns around it too (looked for at 1, 2,
// 4, ... columns), so the tissue between it and a closing vein shears gradually. An open lumen (an
// artery) fixes nothing: the tissue over an artery beside a closing vein sinks with the vein's
// (it stopped at the artery's edge, a tear from the skin down), and the artery is carried whole.
// `fixed_mm`: the distance to the skin or the deep end. Gaussian weights at seven points over +-2
// standard deviations, the neighbours interpolated.
float deform_spread(uint c, uint k, float fixed_mm, DeformParams p)
{
    float own = moved_load(c, k);
    if ((p.flags & DEFORM_PAPER_LINEAR) != 0u) return own;  // the paper's deformation is its columns'
    vec2 walls = walls_load(c, k);
    float dist = min(min(walls.x, walls.y), fixed_mm);
    float reach = min(dist, DEFORM_SPREAD_MAX_MM / DEFORM_SPREAD);  // no nearer lumen matters beyond
    for (uint o = 1u; o < p.columns && float(o) * p.pixel_x_mm < reach; o *= 2u) {
        float dx = float(o) * p.pixel_x_mm;
        float left = c >= o ? walls_load(c - o, k).y : 1e9f, right = c + o < p.columns ? walls_load(c + o, k).y : 1e9f;
        dist = min(dist, sqrt(dx * dx + min(left, right) * min(left, right)));
    }
    float sigma = min(DEFORM_SPREAD * dist, DEFORM_SPREAD_MAX_MM) / p.pixel_x_mm;  // [columns]
    if (sigma < 0.25f) return own;
    float last = float(p.columns - 1u), sum = own, weights = 1.0f;
    for (int t = 1; t <= 3; ++t) {
        float weight = exp2(-float(t * t) * 0.3206f);  // exp(-(2t/3)^2 / 2)
        for (int side = -1; side <= 1; side += 2) {
            float u = clamp(float(c) + float(side * t) * sigma * (2.0f / 3.0f), 0.0f, last);
            uint i = uint(u);
            uint j = min(i + 1u, p.columns - 1u);
            sum += weight * mix(moved_load(i, k), moved_load(j, k), u - float(i));
            weights += weight;
        }
    }
    return sum / weights;
}

// The spread pass: boundary b of column c (1 to its walk's steps), its distance to the skin or the
// deep end as the map's walk counts it, spread (deform_spread) into the spread buffer.
void deform_column_spread(uint c, uint b, DeformParams p)
{
    uint steps = deform_steps(deform_profile(c).x, p);
    if (b == 0u || b > steps) return;
    spread_store(c, b, deform_spread(c, b, min(float(b), float(steps - b)) * p.step_mm, p));
}

// Where a lumen's walls meet, the sound meets two walls in one resolution cell: their echoes become
// one bright line, the sign a sonographer reads as a vein compressed (the live image draws it from
// the labels: bmode_coapted). The recorded volume holds each wall's echo faint and apart, with a
// little blood left between them where they meet (deform_column_solve, walk 1), so the map adds the
// line as a gain: DEFORM_SEAM_DB at the meeting point, fading to none DEFORM_SEAM_MM either side.
// `d`: a pixel's distance from the meeting point [mm].
float deform_seam_db(float d) { return DEFORM_SEAM_DB * max(1.0f - d / DEFORM_SEAM_MM, 0.0f); }

// The last pass, once every column has been solved (and, spread_loaded, its displacements spread
// sideways: deform_column_spread): each pixel of the column mapped back to the depth it came from
// (inverse warp: no holes), with the gain the closed lumens above it make.
void deform_column_map(uint c, DeformParams p)
{
    vec2 profile = deform_profile(c);
    float skin_y = profile.x, shift = profile.y;
    float h = p.step_mm;
    uint steps = deform_steps(skin_y, p);
    uint r = 0u;
    while (r < p.rows && pixel_y(r, p.pixel_y_mm) < skin_y + shift) {  // the gel above the skin moves with it
        map_store(r * p.columns + c, vec2(pixel_y(r, p.pixel_y_mm) - shift, 0.0f));
        ++r;
    }
    float gain = 0.0f;
    // the gain across the beam (deform_gain_band): the neighbours' gains above the step, summed
    // from the first step where one has a gain to the last; elsewhere they are none, or the sums
    // at the last. A column far from any changing lumen, the common case, keeps its own: none.
    GainBand band = deform_gain_band(c, p);
    bool across = (p.flags & DEFORM_PAPER_LINEAR) == 0u && band.steps_with_gain.x > 0u;
    vec4 sums = vec4(0.0f);
    float norm = 1.0f + dot(band.weight, vec4(1.0f));
    float top = skin_y + shift;  // where step k's upper boundary lies now
    float carried = 0.0f;  // how far the spread carries the lumen the walk is in past its column's place
    bool in_lumen = false;
    float seam = -1e9f;  // where the walls of the last lumen the walk passed met (deform_seam_db) [mm]
    // the loads a step needs from the passes before are issued a step ahead (w and next, spread and
    // spread_next), so a GPU's column thread does not wait out each one's latency at its step
    vec4 w = steps > 0u ? scratch_load(c, 0u) : vec4(0.0f);
    float spread = spread_loaded() && steps > 0u ? spread_load(c, 1u) : 0.0f;
    for (uint k = 0u; k < steps && r < p.rows; ++k) {
        vec4 next = k + 1u < steps ? scratch_load(c, k + 1u) : vec4(0.0f);
        float spread_next = spread_loaded() && k + 2u <= steps ? spread_load(c, k + 2u) : 0.0f;
        // the boundary below step k: (k + 1) h from the skin, (steps - k - 1) h from the deep end.
        // A lumen keeps the length its own column gives it (an artery its round shape, a vein what
        // the pressure leaves of it) and is carried whole, as far as the spread moved its upper
        // wall, where it lies now: the tissue around it shears, not the lumen (a closing vein's
        // walls take no spread, so it is carried nowhere)
        if (is_lumen(w) && !in_lumen) carried = (top - skin_y - float(k) * h) - moved_load(c, k);
        in_lumen = is_lumen(w);
        float below = in_lumen          ? moved_load(c, k + 1u) + carried
                      : spread_loaded() ? spread
                                        : deform_spread(c, k + 1u, min(float(k + 1u), float(steps - k - 1u)) * h, p);
        float bottom = skin_y + float(k + 1u) * h + below;
        float length = bottom - top;
        float shown = across ? (gain + dot(band.weight, sums)) / norm : gain;
        // a lumen whose walls meet begins below this step: their echo straddles its bottom
        float meets = !is_lumen(w) && is_lumen(next) && next.z >= DEFORM_SEAM_CLOSURE ? max(top, bottom) : 1e9f;
        while (r < p.rows && pixel_y(r, p.pixel_y_mm) < bottom) {
            float y = pixel_y(r, p.pixel_y_mm);
            float f = length > 0.0f ? clamp((y - top) / length, 0.0f, 1.0f) : 0.0f;
            map_store(r * p.columns + c, vec2(skin_y + (float(k) + f) * h, shown + deform_seam_db(min(abs(y - seam), abs(y - meets)))));
            ++r;
        }
        top = max(top, bottom);  // a boundary the spread moved above the last one folds nothing back
        seam = meets < 1e8f ? meets : seam;
        gain += is_lumen(w) ? w.w : 0.0f;
        if (across && k + 1u >= band.steps_with_gain.x && k < band.steps_with_gain.y) sums = deform_gain_step(band, k, sums);
        w = next;
        spread = spread_next;
    }
    // what the neighbours' lumens below the column's last walked step add
    for (uint k = steps; across && k < band.steps_with_gain.y; ++k) sums = deform_gain_step(band, k, sums);
    float shown = across ? (gain + dot(band.weight, sums)) / norm : gain;
    float rest = moved_load(c, steps);  // what the column could not take up moves the tissue below
    while (r < p.rows) {
        float y = pixel_y(r, p.pixel_y_mm);
        map_store(r * p.columns + c, vec2(y - rest, shown + deform_seam_db(abs(y - seam))));
        ++r;
    }
}

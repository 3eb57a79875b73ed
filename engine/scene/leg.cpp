#include "scene/leg.hpp"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace echosim::scene {
namespace {

constexpr float kTableTopY = 95.0f;  // [mm] posterior skin of the legs rests here
constexpr glm::vec3 kSkin{0.62f, 0.38f, 0.28f};
constexpr glm::vec3 kDrape{0.10f, 0.30f, 0.36f};
constexpr glm::vec3 kTable{0.05f, 0.06f, 0.08f};
constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

// One limb station: z level, centre x, and half-widths medial, lateral, posterior, anterior [mm].
// The centre's y is set so the posterior skin rests on the table.
Station limb_station(float z, float cx, float medial, float lateral, float posterior, float anterior, float mirror)
{
    const float cy = kTableTopY - posterior;
    // e1 = +x is medial for the right leg and lateral for the left one (mirror = -1)
    return mirror > 0 ? Station{{cx, cy, z}, medial, lateral, posterior, anterior}
                      : Station{{-cx, cy, z}, lateral, medial, posterior, anterior};
}

Tube make_leg(float mirror)
{
    Tube t;
    t.e1 = {1, 0, 0};
    t.e2 = {0, 1, 0};
    // hip dome (hidden by the drape), thigh tapering to the knee, calf bulging posteriorly, ankle
    t.stations = {
        limb_station(60, -100, 30, 30, 30, 30, mirror),  limb_station(40, -100, 72, 80, 72, 70, mirror),
        limb_station(0, -97, 86, 92, 88, 82, mirror),     limb_station(-120, -94, 80, 86, 80, 76, mirror),
        limb_station(-250, -90, 70, 76, 70, 66, mirror),  limb_station(-370, -86, 58, 62, 56, 56, mirror),
        limb_station(-440, -84, 52, 54, 50, 55, mirror),  limb_station(-500, -84, 46, 48, 48, 46, mirror),
        limb_station(-580, -83, 48, 48, 62, 40, mirror),  limb_station(-700, -82, 38, 38, 44, 34, mirror),
        limb_station(-800, -80, 28, 30, 30, 30, mirror),  limb_station(-845, -80, 25, 27, 27, 27, mirror),
        limb_station(-858, -80, 10, 10, 10, 10, mirror),
    };
    return t;
}

Tube make_foot(float mirror)
{
    // supine: the sole faces inferior (-z), the toes point anterior (-y, up from the table)
    Tube t;
    t.e1 = {1, 0, 0};
    t.e2 = {0, 0, 1};
    const float x = -80.0f * mirror;
    auto st = [&](float y, float z, float ml, float dorsum, float sole) {
        return Station{{x, y, z}, ml, ml, dorsum, sole, 2.2f};
    };
    t.stations = {st(88, -868, 14, 14, 14), st(72, -872, 27, 30, 24), st(30, -878, 36, 30, 20),
                  st(-30, -882, 42, 22, 14), st(-95, -884, 43, 14, 10), st(-122, -884, 32, 8, 6),
                  st(-128, -884, 10, 3, 3)};
    return t;
}

Tube make_pelvis()
{
    Tube t;
    t.e1 = {1, 0, 0};
    t.e2 = {0, 1, 0};
    auto st = [](float z, float rx, float ant, float post) { return Station{{0, kTableTopY - post, z}, rx, rx, post, ant, 2.4f}; };
    t.stations = {st(-8, 192, 100, 96), st(60, 188, 106, 96), st(180, 172, 100, 96), st(270, 162, 96, 92)};
    return t;
}

int nearest_ring(const Tube& tube, int rings_per_span, float z)
{
    const int rings = int(tube.stations.size() - 1) * rings_per_span + 1;
    int best = 0;
    for (int i = 1; i < rings; ++i)
        if (std::abs(tube.at(float(i) / float(rings_per_span)).center.z - z) <
            std::abs(tube.at(float(best) / float(rings_per_span)).center.z - z))
            best = i;
    return best;
}

}  // namespace

LegModel::LegModel(const LegOptions& options)
    : options_(options), right_leg_(make_leg(+1)), left_leg_(make_leg(-1)), right_foot_(make_foot(+1)),
      left_foot_(make_foot(-1)), pelvis_(make_pelvis())
{
    // the patch: 120 mm of the proximal thigh below the groin, about 80 mm around it, centred
    // anterior-medially over the common and superficial femoral vessels
    const int ring0 = nearest_ring(right_leg_, options.rings_per_span, -30.0f);
    const int ring1 = nearest_ring(right_leg_, options.rings_per_span, -150.0f);
    const float seg_angle = 2.0f * std::numbers::pi_v<float> / float(options.segments);
    const int seg0 = int(std::lround(278.0f * kDeg / seg_angle));
    const int seg1 = int(std::lround(332.0f * kDeg / seg_angle));

    TubeMeshOptions leg_mesh;
    leg_mesh.rings_per_span = options.other_rings_per_span;
    leg_mesh.segments = options.other_segments;
    leg_mesh.color = kSkin;
    static_mesh_ = build_tube(left_leg_, leg_mesh);
    leg_mesh.rings_per_span = options.rings_per_span;
    leg_mesh.segments = options.segments;
    leg_mesh.skip_cell = [&](int ring, int seg) { return ring >= ring0 && ring < ring1 && seg >= seg0 && seg < seg1; };
    static_mesh_.append(build_tube(right_leg_, leg_mesh));

    TubeMeshOptions foot_mesh;
    foot_mesh.rings_per_span = 8;
    foot_mesh.segments = 48;
    foot_mesh.color = kSkin;
    static_mesh_.append(build_tube(right_foot_, foot_mesh));
    static_mesh_.append(build_tube(left_foot_, foot_mesh));

    TubeMeshOptions drape_mesh;
    drape_mesh.rings_per_span = 8;
    drape_mesh.segments = 96;
    drape_mesh.color = kDrape;
    drape_mesh.flat_cap_color = kDrape * 0.8f;
    drape_mesh.start = Cap::flat;
    drape_mesh.end = Cap::flat;
    static_mesh_.append(build_tube(pelvis_, drape_mesh));
    static_mesh_.append(make_box({-330, kTableTopY, -990}, {330, kTableTopY + 40, 320}, kTable));

    // the patch samples the same surface, patch_refine times finer than the leg
    const int r = options.patch_refine;
    patch_.rows = (ring1 - ring0) * r + 1;
    patch_.cols = (seg1 - seg0) * r + 1;
    patch_.t0 = float(ring0) / float(options.rings_per_span);
    patch_.t1 = float(ring1) / float(options.rings_per_span);
    patch_.theta0 = float(seg0) * seg_angle;
    patch_.theta1 = float(seg1) * seg_angle;
    const float dt = 1.0f / float(options.rings_per_span);
    auto surface = [&](int i, int j) {
        // fine vertex (i, j) sits at leg cell coordinates (ring0 + i/r, seg0 + j/r)
        const int ci = i / r, cj = j / r, fi = i % r, fj = j % r;
        const float t = (float(ring0 * r + i) / float(r)) * dt;
        const float th = (float(seg0 * r + j) / float(r)) * seg_angle;
        const bool on_edge_row = i == 0 || i == patch_.rows - 1;
        const bool on_edge_col = j == 0 || j == patch_.cols - 1;
        glm::vec3 p = right_leg_.point(t, th);
        // border vertices between two leg vertices lie on the leg's straight edge, not on the smooth
        // surface, so the patch closes the hole without cracks (T-junctions on a chord)
        if (on_edge_row && fj != 0) {
            const float ring_t = float(ring0 + ci) * dt;
            const glm::vec3 a = right_leg_.point(ring_t, float(seg0 + cj) * seg_angle);
            const glm::vec3 b = right_leg_.point(ring_t, float(seg0 + cj + 1) * seg_angle);
            p = a + (b - a) * (float(fj) / float(r));
        } else if (on_edge_col && fi != 0) {
            const float seg_th = float(seg0 + cj) * seg_angle;
            const glm::vec3 a = right_leg_.point(float(ring0 + ci) * dt, seg_th);
            const glm::vec3 b = right_leg_.point(float(ring0 + ci + 1) * dt, seg_th);
            p = a + (b - a) * (float(fi) / float(r));
        }
        return Vertex{p, right_leg_.outward_normal(t, th), kSkin};
    };
    for (int i = 0; i < patch_.rows; ++i)
        for (int j = 0; j < patch_.cols; ++j) patch_.rest.vertices.push_back(surface(i, j));
    for (int i = 0; i + 1 < patch_.rows; ++i)
        for (int j = 0; j + 1 < patch_.cols; ++j) {
            const auto a = std::uint32_t(i * patch_.cols + j), b = a + 1, c = a + std::uint32_t(patch_.cols), d = c + 1;
            for (std::uint32_t k : {a, c, d, a, d, b}) patch_.rest.indices.push_back(k);
        }
    orient_to_normals(patch_.rest);
}

glm::vec3 LegModel::patch_point(float u, float v) const
{
    return right_leg_.point(patch_.t0 + (patch_.t1 - patch_.t0) * u, patch_.theta0 + (patch_.theta1 - patch_.theta0) * v);
}

glm::vec3 LegModel::patch_normal(float u, float v) const
{
    return right_leg_.outward_normal(patch_.t0 + (patch_.t1 - patch_.t0) * u,
                                     patch_.theta0 + (patch_.theta1 - patch_.theta0) * v);
}

Pose LegModel::probe_rest_pose(float u, float v) const
{
    const float dv = 1e-3f;
    const glm::vec3 around = patch_point(u, v + dv) - patch_point(u, v - dv);
    return pose_from_axes(patch_point(u, v), around, -patch_normal(u, v));
}

Mesh make_linear_probe(const ProbeSpec& spec)
{
    // a tube along -y: lens face, head, tapered neck, grip, strain relief and a cable stub
    Tube t;
    t.e1 = {1, 0, 0};
    t.e2 = {0, 0, 1};
    const float hw = float(spec.face_width_mm / 2), ht = float(spec.face_thickness_mm / 2);
    auto st = [](float y, float rx, float rz, float n) { return Station{{0, y, 0}, rx, rx, rz, rz, n}; };
    t.stations = {st(0, hw, ht, 6), st(-4, hw + 1, ht + 2, 5), st(-22, hw + 1, ht + 5, 4), st(-40, 16, 12, 3),
                  st(-75, 14, 13, 2.5f), st(-105, 15, 14, 2.5f), st(-118, 8, 8, 2), st(-135, 4, 4, 2), st(-190, 3.5f, 3.5f, 2)};
    TubeMeshOptions o;
    o.rings_per_span = 6;
    o.segments = 48;
    o.color = {0.82f, 0.83f, 0.85f};
    o.start = Cap::flat;
    o.flat_cap_color = {0.08f, 0.09f, 0.10f};  // the acoustic lens
    o.end = Cap::flat;
    Mesh m = build_tube(t, o);
    // the cable is dark
    for (auto& v : m.vertices)
        if (v.position.y < -120.0f) v.color = {0.12f, 0.12f, 0.13f};
    return m;
}

}  // namespace echosim::scene

#include "scene/leg.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

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

int wrap(int i, int n) { return ((i % n) + n) % n; }

// the index in `cumulative` (increasing) whose value is nearest to `s`
int nearest_index(const std::vector<float>& cumulative, float s)
{
    int best = 0;
    for (int i = 1; i < int(cumulative.size()); ++i)
        if (std::abs(cumulative[std::size_t(i)] - s) < std::abs(cumulative[std::size_t(best)] - s)) best = i;
    return best;
}

}  // namespace

LegModel::LegModel(const LegOptions& options)
    : options_(options), right_leg_(make_leg(+1)), left_leg_(make_leg(-1)), right_foot_(make_foot(+1)),
      left_foot_(make_foot(-1)), pelvis_(make_pelvis())
{
    if (options.rings_per_span < 1 || options.segments < 8 || options.patch_refine < 1)
        throw std::invalid_argument("LegOptions: rings_per_span " + std::to_string(options.rings_per_span) + ", segments " +
                                    std::to_string(options.segments) + ", patch_refine " + std::to_string(options.patch_refine) +
                                    ": need >= 1, >= 8, >= 1");
    const int rps = options.rings_per_span, segs = options.segments;
    const float seg_angle = 2.0f * std::numbers::pi_v<float> / float(segs);
    const int rings = int(right_leg_.stations.size() - 1) * rps + 1;
    // a vertex of the leg mesh, computed as build_tube computes it, so shared borders are bit-equal
    auto leg_vertex = [&](int ring, int seg) { return right_leg_.point(float(ring) / float(rps), float(wrap(seg, segs)) * seg_angle); };

    // the home patch: 120 mm of the proximal thigh below the groin, about 80 mm around it, centred
    // anterior-medially over the common and superficial femoral vessels
    const PatchCells home{nearest_ring(right_leg_, rps, -30.0f), nearest_ring(right_leg_, rps, -150.0f),
                     int(std::lround(278.0f * kDeg / seg_angle)), int(std::lround(332.0f * kDeg / seg_angle))};
    {
        const int mid_seg = (home.seg0 + home.seg1) / 2, mid_ring = (home.ring0 + home.ring1) / 2;
        for (int i = home.ring0; i < home.ring1; ++i)
            window_along_mm_ += glm::length(leg_vertex(i + 1, mid_seg) - leg_vertex(i, mid_seg));
        for (int j = home.seg0; j < home.seg1; ++j)
            window_around_mm_ += glm::length(leg_vertex(mid_ring, j + 1) - leg_vertex(mid_ring, j));
    }
    ring_z_.resize(std::size_t(rings));
    for (int i = 0; i < rings; ++i) ring_z_[std::size_t(i)] = right_leg_.at(float(i) / float(rps)).center.z;
    const PatchCells c = options.patch_centre ? window_cells(*options.patch_centre) : home;

    TubeMeshOptions leg_mesh;
    leg_mesh.rings_per_span = options.other_rings_per_span;
    leg_mesh.segments = options.other_segments;
    leg_mesh.color = kSkin;
    static_mesh_ = build_tube(left_leg_, leg_mesh);
    leg_mesh.rings_per_span = rps;
    leg_mesh.segments = segs;
    leg_mesh.skip_cell = [&](int ring, int seg) {
        return ring >= c.ring0 && ring < c.ring1 && wrap(seg - c.seg0, segs) < c.seg1 - c.seg0;
    };
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
    patch_.cells = c;
    patch_.rows = (c.ring1 - c.ring0) * r + 1;
    patch_.cols = (c.seg1 - c.seg0) * r + 1;
    patch_.t0 = float(c.ring0) / float(rps);
    patch_.t1 = float(c.ring1) / float(rps);
    patch_.theta0 = float(c.seg0) * seg_angle;
    patch_.theta1 = float(c.seg1) * seg_angle;
    {
        // the middle in millimetres: halfway along the chords of a fine line through the window
        constexpr int pieces = 256;
        auto halfway = [](auto&& point, float from, float to) {
            std::vector<float> s(pieces + 1, 0.0f);
            for (int k = 1; k <= pieces; ++k)
                s[std::size_t(k)] = s[std::size_t(k - 1)] + glm::length(point(from + (to - from) * float(k) / pieces) -
                                                                         point(from + (to - from) * float(k - 1) / pieces));
            const float half = 0.5f * s.back();
            int k = 1;
            while (k < pieces && s[std::size_t(k)] < half) ++k;
            const float f = (half - s[std::size_t(k - 1)]) / std::max(1e-6f, s[std::size_t(k)] - s[std::size_t(k - 1)]);
            return from + (to - from) * (float(k - 1) + f) / pieces;
        };
        const float mid_theta = 0.5f * (patch_.theta0 + patch_.theta1);
        patch_.centre.t = halfway([&](float t) { return right_leg_.point(t, mid_theta); }, patch_.t0, patch_.t1);
        const float th = halfway([&](float a) { return right_leg_.point(patch_.centre.t, a); }, patch_.theta0, patch_.theta1);
        patch_.centre.theta = std::fmod(th + 4.0f * std::numbers::pi_v<float>, 2.0f * std::numbers::pi_v<float>);
    }
    const float dt = 1.0f / float(rps);
    auto surface = [&](int i, int j) {
        // fine vertex (i, j) sits at leg cell coordinates (ring0 + i/r, seg0 + j/r)
        const int ci = i / r, cj = j / r, fi = i % r, fj = j % r;
        const float t = (float(c.ring0 * r + i) / float(r)) * dt;
        const float th = (float(c.seg0 * r + j) / float(r)) * seg_angle;
        const bool on_edge_row = i == 0 || i == patch_.rows - 1;
        const bool on_edge_col = j == 0 || j == patch_.cols - 1;
        glm::vec3 p = right_leg_.point(t, th);
        // border vertices between two leg vertices lie on the leg's straight edge, not on the smooth
        // surface, so the patch closes the hole without cracks (T-junctions on a chord); those on a
        // leg vertex are that vertex, bit for bit
        if (on_edge_row && fj != 0) {
            const glm::vec3 a = leg_vertex(c.ring0 + ci, c.seg0 + cj);
            const glm::vec3 b = leg_vertex(c.ring0 + ci, c.seg0 + cj + 1);
            p = a + (b - a) * (float(fj) / float(r));
        } else if (on_edge_col && fi != 0) {
            const glm::vec3 a = leg_vertex(c.ring0 + ci, c.seg0 + cj);
            const glm::vec3 b = leg_vertex(c.ring0 + ci + 1, c.seg0 + cj);
            p = a + (b - a) * (float(fi) / float(r));
        } else if (on_edge_row || on_edge_col) {
            p = leg_vertex(c.ring0 + ci, c.seg0 + cj);
        }
        return Vertex{p, right_leg_.outward_normal(t, th), kSkin};
    };
    for (int i = 0; i < patch_.rows; ++i)
        for (int j = 0; j < patch_.cols; ++j) patch_.rest.vertices.push_back(surface(i, j));
    for (int i = 0; i + 1 < patch_.rows; ++i)
        for (int j = 0; j + 1 < patch_.cols; ++j) {
            const auto a = std::uint32_t(i * patch_.cols + j), b = a + 1, below = a + std::uint32_t(patch_.cols), d = below + 1;
            for (std::uint32_t k : {a, below, d, a, d, b}) patch_.rest.indices.push_back(k);
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

PatchCells LegModel::window_cells(LimbCoordinates centre) const
{
    const int rps = options_.rings_per_span, segs = options_.segments;
    const float seg_angle = 2.0f * std::numbers::pi_v<float> / float(segs);
    const int rings = int(ring_z_.size());
    auto leg_vertex = [&](int ring, int seg) { return right_leg_.point(float(ring) / float(rps), float(wrap(seg, segs)) * seg_angle); };
    PatchCells c;
    // a window of the home patch's size in millimetres, in whole cells, centred on the leg cell
    // boundaries nearest to the asked centre; kept between the hip (t = 1, under the drape above)
    // and the ankle (a span short of the limb's end)
    const LimbCoordinates at = centre;
    if (!std::isfinite(at.t) || !std::isfinite(at.theta))
        throw std::invalid_argument("LegOptions::patch_centre: t " + std::to_string(at.t) + ", theta " + std::to_string(at.theta) +
                                    ": must be finite");
    const int lo = rps, hi = rings - 1 - rps;
    const float ring_c = std::clamp(at.t * float(rps), float(lo), float(hi));
    const float seg_c = std::fmod(at.theta, 2.0f * std::numbers::pi_v<float>) / seg_angle;
    const int seg_mid = int(std::floor(seg_c));
    // along: the skin's length over the rings, through the segment nearest the centre
    std::vector<float> along(std::size_t(rings), 0.0f);
    const int seg_line = int(std::lround(seg_c));
    for (int i = 1; i < rings; ++i)
        along[std::size_t(i)] = along[std::size_t(i - 1)] + glm::length(leg_vertex(i, seg_line) - leg_vertex(i - 1, seg_line));
    const int rc = std::min(int(std::floor(ring_c)), rings - 2);
    const float s_c = along[std::size_t(rc)] + (ring_c - float(rc)) * (along[std::size_t(rc + 1)] - along[std::size_t(rc)]);
    c.ring0 = nearest_index(along, s_c - 0.5f * window_along_mm_);
    c.ring1 = nearest_index(along, s_c + 0.5f * window_along_mm_);
    if (c.ring0 < lo) {
        c.ring0 = lo;
        c.ring1 = nearest_index(along, along[std::size_t(lo)] + window_along_mm_);
    }
    if (c.ring1 > hi) {
        c.ring1 = hi;
        c.ring0 = std::max(lo, nearest_index(along, along[std::size_t(hi)] - window_along_mm_));
    }
    c.ring1 = std::max(c.ring1, c.ring0 + 1);
    // around: the skin's length over the segments, through the ring nearest the centre
    const int ring_line = (c.ring0 + c.ring1) / 2;
    const int first = seg_mid - segs / 2;  // around[k] is at segment first + k
    std::vector<float> around(std::size_t(segs) + 1, 0.0f);
    for (int k = 1; k <= segs; ++k)
        around[std::size_t(k)] = around[std::size_t(k - 1)] +
                                 glm::length(leg_vertex(ring_line, first + k) - leg_vertex(ring_line, first + k - 1));
    const int k0 = seg_mid - first;
    const float a_c = around[std::size_t(k0)] + (seg_c - float(seg_mid)) * (around[std::size_t(k0 + 1)] - around[std::size_t(k0)]);
    c.seg0 = first + nearest_index(around, a_c - 0.5f * window_around_mm_);
    c.seg1 = std::max(c.seg0 + 1, first + nearest_index(around, a_c + 0.5f * window_around_mm_));
    // seg0 in [0, segs): one name for each window
    const int shift = wrap(c.seg0, segs) - c.seg0;
    c.seg0 += shift;
    c.seg1 += shift;
    return c;
}

Pose LegModel::limb_rest_pose(LimbCoordinates c) const
{
    const float dtheta = 1e-3f;
    const glm::vec3 around = right_leg_.point(c.t, c.theta + dtheta) - right_leg_.point(c.t, c.theta - dtheta);
    return pose_from_axes(limb_point(c), around, -limb_normal(c));
}

float LegModel::limb_t_at_z(float z) const
{
    // the rings' planes descend with t (the stations do, and the spline between them keeps to it
    // on this leg): bracket z between two rings, then bisect the spline there
    const int n = int(ring_z_.size());
    if (z >= ring_z_.front()) return 0.0f;
    if (z <= ring_z_.back()) return right_leg_.t_max();
    int i = 0;
    while (i + 2 < n && ring_z_[std::size_t(i + 1)] > z) ++i;
    const float rps = float(options_.rings_per_span);
    float lo = float(i) / rps, hi = float(i + 1) / rps;
    for (int k = 0; k < 24; ++k) {
        const float mid = 0.5f * (lo + hi);
        (right_leg_.at(mid).center.z > z ? lo : hi) = mid;
    }
    return 0.5f * (lo + hi);
}

LimbCoordinates LegModel::limb_coordinates(glm::vec3 p) const
{
    LimbCoordinates c;
    c.t = limb_t_at_z(p.z);
    const glm::vec3 d = p - right_leg_.at(c.t).center;
    float th = std::atan2(glm::dot(d, right_leg_.e2), glm::dot(d, right_leg_.e1));
    if (th < 0) th += 2.0f * std::numbers::pi_v<float>;
    c.theta = th;
    return c;
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
    // the cable is dark; the head's -x end is the orientation marker (a probe's notch or light)
    for (auto& v : m.vertices) {
        if (v.position.y < -120.0f) v.color = {0.12f, 0.12f, 0.13f};
        if (v.position.y < -3.0f && v.position.y > -23.0f && v.position.x < -0.8f * hw) v.color = kMarkerColour;
    }
    return m;
}

}  // namespace echosim::scene

#include "scene/tube.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace echosim::scene {
namespace {

float catmull_rom(float p0, float p1, float p2, float p3, float s)
{
    const float s2 = s * s;
    const float s3 = s2 * s;
    return 0.5f * (2.0f * p1 + (-p0 + p2) * s + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * s2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * s3);
}

glm::vec3 catmull_rom(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, float s)
{
    return {catmull_rom(a.x, b.x, c.x, d.x, s), catmull_rom(a.y, b.y, c.y, d.y, s), catmull_rom(a.z, b.z, c.z, d.z, s)};
}

}  // namespace

Station Tube::at(float t) const
{
    const int n = int(stations.size());
    t = std::clamp(t, 0.0f, t_max());
    const int i = std::min(int(std::floor(t)), n - 2);
    const float s = t - float(i);
    const Station& a = stations[std::max(i - 1, 0)];
    const Station& b = stations[i];
    const Station& c = stations[i + 1];
    const Station& d = stations[std::min(i + 2, n - 1)];
    Station r;
    r.center = catmull_rom(a.center, b.center, c.center, d.center, s);
    // radii never go below zero even where the spline overshoots
    r.r_pos1 = std::max(0.0f, catmull_rom(a.r_pos1, b.r_pos1, c.r_pos1, d.r_pos1, s));
    r.r_neg1 = std::max(0.0f, catmull_rom(a.r_neg1, b.r_neg1, c.r_neg1, d.r_neg1, s));
    r.r_pos2 = std::max(0.0f, catmull_rom(a.r_pos2, b.r_pos2, c.r_pos2, d.r_pos2, s));
    r.r_neg2 = std::max(0.0f, catmull_rom(a.r_neg2, b.r_neg2, c.r_neg2, d.r_neg2, s));
    r.exponent = b.exponent + (c.exponent - b.exponent) * s;
    return r;
}

glm::vec3 Tube::point(float t, float theta) const
{
    const Station st = at(t);
    const float c = std::cos(theta);
    const float s = std::sin(theta);
    const float a1 = c >= 0.0f ? st.r_pos1 : st.r_neg1;
    const float a2 = s >= 0.0f ? st.r_pos2 : st.r_neg2;
    // super-ellipse |x/a1|^n + |y/a2|^n = 1 along the ray at angle theta
    const float n = st.exponent;
    const float k = std::pow(std::pow(std::abs(c) / std::max(a1, 1e-6f), n) + std::pow(std::abs(s) / std::max(a2, 1e-6f), n),
                             -1.0f / n);
    return st.center + e1 * (k * c) + e2 * (k * s);
}

glm::vec3 Tube::outward_normal(float t, float theta) const
{
    constexpr float dt = 1e-3f;
    constexpr float dtheta = 1e-3f;
    const float t0 = std::max(0.0f, t - dt), t1 = std::min(t_max(), t + dt);
    const glm::vec3 along = point(t1, theta) - point(t0, theta);
    const glm::vec3 around = point(t, theta + dtheta) - point(t, theta - dtheta);
    glm::vec3 n = glm::cross(around, along);
    const float len = glm::length(n);
    if (len < 1e-12f) return glm::normalize(point(t, theta) - at(t).center);
    n /= len;
    if (glm::dot(n, point(t, theta) - at(t).center) < 0.0f) n = -n;
    return n;
}

Mesh build_tube(const Tube& tube, const TubeMeshOptions& o)
{
    Mesh m;
    const int rings = int(tube.stations.size() - 1) * o.rings_per_span + 1;
    const float dtheta = 2.0f * std::numbers::pi_v<float> / float(o.segments);
    m.vertices.reserve(std::size_t(rings * o.segments + 2 * (o.segments + 1)));
    for (int i = 0; i < rings; ++i) {
        const float t = float(i) / float(o.rings_per_span);
        for (int j = 0; j < o.segments; ++j) {
            const float theta = float(j) * dtheta;
            m.vertices.push_back({tube.point(t, theta), tube.outward_normal(t, theta), o.color});
        }
    }
    auto idx = [&](int i, int j) { return std::uint32_t(i * o.segments + (j % o.segments)); };
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < o.segments; ++j) {
            if (o.skip_cell && o.skip_cell(i, j)) continue;
            for (std::uint32_t k : {idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)})
                m.indices.push_back(k);
        }

    auto cap = [&](Cap kind, int ring, float t, float sign) {
        if (kind == Cap::none) return;
        const glm::vec3 center = tube.at(t).center;
        // the cap faces away from the tube's inside
        const glm::vec3 inward = tube.at(std::clamp(t + sign * 0.05f, 0.0f, tube.t_max())).center - center;
        const glm::vec3 axis = glm::length(inward) > 1e-6f ? glm::normalize(inward) : glm::cross(tube.e1, tube.e2);
        if (kind == Cap::pointed) {
            // close the ring on its own centre: smooth when the last station is already small
            const auto c = std::uint32_t(m.vertices.size());
            m.vertices.push_back({center, -axis, o.color});
            for (int j = 0; j < o.segments; ++j)
                for (std::uint32_t k : {c, idx(ring, j), idx(ring, j + 1)}) m.indices.push_back(k);
            return;
        }
        // flat: a disc of its own vertices so the rim stays sharp
        const auto base = std::uint32_t(m.vertices.size());
        m.vertices.push_back({center, -axis, o.flat_cap_color});
        for (int j = 0; j < o.segments; ++j)
            m.vertices.push_back({m.vertices[idx(ring, j)].position, -axis, o.flat_cap_color});
        for (int j = 0; j < o.segments; ++j)
            for (std::uint32_t k : {base, base + 1 + std::uint32_t(j), base + 1 + std::uint32_t((j + 1) % o.segments)})
                m.indices.push_back(k);
    };
    cap(o.start, 0, 0.0f, +1.0f);
    cap(o.end, rings - 1, tube.t_max(), -1.0f);
    orient_to_normals(m);
    return m;
}

}  // namespace echosim::scene

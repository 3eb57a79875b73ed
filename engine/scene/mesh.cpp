#include "scene/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace echosim::scene {

void Mesh::append(const Mesh& other)
{
    const auto base = std::uint32_t(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    indices.reserve(indices.size() + other.indices.size());
    for (std::uint32_t i : other.indices) indices.push_back(base + i);
}

Bounds bounds(const Mesh& mesh)
{
    Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (const auto& v : mesh.vertices) {
        b.min = glm::min(b.min, v.position);
        b.max = glm::max(b.max, v.position);
    }
    return b;
}

void recompute_normals(Mesh& mesh)
{
    for (auto& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        auto& a = mesh.vertices[mesh.indices[t]];
        auto& b = mesh.vertices[mesh.indices[t + 1]];
        auto& c = mesh.vertices[mesh.indices[t + 2]];
        // the cross product's length is twice the area: larger triangles weigh more
        const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
        a.normal += n;
        b.normal += n;
        c.normal += n;
    }
    for (auto& v : mesh.vertices) {
        const float len = glm::length(v.normal);
        v.normal = len > 0.0f ? v.normal / len : glm::vec3(0.0f, -1.0f, 0.0f);
    }
}

void orient_to_normals(Mesh& mesh)
{
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const auto& a = mesh.vertices[mesh.indices[t]];
        const auto& b = mesh.vertices[mesh.indices[t + 1]];
        const auto& c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(face, a.normal + b.normal + c.normal) < 0.0f) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
}

Mesh make_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 color, float max_cell_mm)
{
    if (!(max_cell_mm > 0.0f)) throw std::invalid_argument("make_box: max_cell_mm must be positive");
    Mesh m;
    // each face has its own vertices so the edges stay sharp
    const std::array<glm::vec3, 6> normals = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                              glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
    const glm::vec3 half = (hi - lo) * 0.5f;
    for (const glm::vec3& n : normals) {
        // two tangents spanning the face, and the face's half extents along them
        const glm::vec3 u = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 v = glm::cross(n, u);
        const glm::vec3 centre = (lo + hi) * 0.5f + n * half;
        const float hu = glm::dot(glm::abs(u), half), hv = glm::dot(glm::abs(v), half);
        const int cu = std::max(1, int(std::ceil(2.0f * hu / max_cell_mm)));
        const int cv = std::max(1, int(std::ceil(2.0f * hv / max_cell_mm)));
        const auto base = std::uint32_t(m.vertices.size());
        for (int j = 0; j <= cv; ++j)
            for (int i = 0; i <= cu; ++i) {
                const float su = -1.0f + 2.0f * float(i) / float(cu), sv = -1.0f + 2.0f * float(j) / float(cv);
                m.vertices.push_back({centre + su * hu * u + sv * hv * v, n, color});
            }
        const auto at = [&](int i, int j) { return base + std::uint32_t(j * (cu + 1) + i); };
        for (int j = 0; j < cv; ++j)
            for (int i = 0; i < cu; ++i)
                for (std::uint32_t k : {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)})
                    m.indices.push_back(k);
    }
    orient_to_normals(m);
    return m;
}

}  // namespace echosim::scene

#include "scene/mesh.hpp"

#include <algorithm>
#include <array>

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

Mesh make_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 color)
{
    Mesh m;
    // one quad per face, each with its own four vertices so the edges stay sharp
    const std::array<glm::vec3, 6> normals = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                              glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
    for (const glm::vec3& n : normals) {
        // two tangents spanning the face
        const glm::vec3 u = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 v = glm::cross(n, u);
        const glm::vec3 centre = (lo + hi) * 0.5f + n * (hi - lo) * 0.5f;
        const glm::vec3 half = (hi - lo) * 0.5f;
        const auto base = std::uint32_t(m.vertices.size());
        for (const auto& [su, sv] : std::array<std::pair<float, float>, 4>{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}})
            m.vertices.push_back({centre + su * u * half + sv * v * half, n, color});
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
    }
    orient_to_normals(m);
    return m;
}

}  // namespace echosim::scene

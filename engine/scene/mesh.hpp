// Triangle meshes as the scene pass (render/scene_pass) takes them: positions in world millimetres (LPS), unit normals,
// linear-RGB colours. Builders in this folder make the leg, the exam patch and the probe.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace echosim::scene {

struct Vertex {
    glm::vec3 position;  // [mm]
    glm::vec3 normal;
    glm::vec3 color;  // linear RGB, 0..1
};
static_assert(sizeof(Vertex) == 36, "Vertex is uploaded as is; shaders/mesh.vert reads this layout");

struct Mesh {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles

    void append(const Mesh& other);
};

// Axis-aligned bounds of a mesh's vertices.
struct Bounds {
    glm::vec3 min;
    glm::vec3 max;
};
Bounds bounds(const Mesh& mesh);

// Area-weighted vertex normals from the triangles (for meshes whose shape changes at run time).
void recompute_normals(Mesh& mesh);

// Makes every triangle wind counter-clockwise seen from the side its vertex normals point to, so
// the scene pass can cull back faces (the builders produce outward normals; winding is fixed here).
void orient_to_normals(Mesh& mesh);

// An axis-aligned box with flat faces (the examination table), each face a grid of quads no side
// of which is longer than `max_cell_mm`: the scene lights its static meshes per vertex, and the
// view-dependent terms (the sheen towards grazing angles) need vertices across a large face.
Mesh make_box(glm::vec3 min, glm::vec3 max, glm::vec3 color, float max_cell_mm = 25.0f);

}  // namespace echosim::scene

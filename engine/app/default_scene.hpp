// The scene every part draws by default: the leg, the exam patch at rest, the probe resting on the
// patch centre in transverse orientation, and the default camera. Shared by the commands, the tests
// and the benchmarks, so they all look at the same thing.
#pragma once

#include <vector>

#include "core/pose.hpp"
#include "render/scene_pass.hpp"
#include "scene/camera.hpp"
#include "scene/leg.hpp"
#include "scene/mesh.hpp"

namespace echosim::app {

struct DefaultScene {
    scene::LegModel leg;
    scene::Mesh probe = scene::make_linear_probe();
    std::vector<scene::Vertex> patch = leg.patch().rest.vertices;  // current patch shape
    Pose probe_pose = leg.probe_rest_pose(0.5f, 0.5f);
    scene::OrbitCamera camera;

    render::SceneMeshes meshes() const { return {leg.static_mesh(), leg.patch().rest, probe}; }
    render::FrameView frame_view() const { return {camera, patch, probe_pose.matrix(), true}; }
};

}  // namespace echosim::app

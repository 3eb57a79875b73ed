// The scene every part draws by default: a simulator session (the leg, the exam patch as the tissue
// leaves it, the probe where the session holds it: on the patch centre in transverse orientation
// until moved) seen by the default camera. Shared by the commands, the tests and the benchmarks, so
// they all look at the same thing.
#pragma once

#include "render/scene_pass.hpp"
#include "scene/camera.hpp"
#include "scene/leg.hpp"
#include "scene/mesh.hpp"
#include "session/session.hpp"

namespace echosim::runner {

struct DefaultScene {
    session::Session session;
    scene::Mesh probe_mesh = scene::make_linear_probe();
    scene::OrbitCamera camera;

    explicit DefaultScene(const session::SessionOptions& options = {}) : session(options) {}

    render::SceneMeshes meshes() const { return {session.leg().static_mesh(), session.leg().patch().rest, probe_mesh}; }
    // the session's newest state, from the camera
    render::FrameView frame_view() { return frame_view(session.view()); }
    // a view already taken (so the frame's scene and its echographic image show one physics step)
    render::FrameView frame_view(const session::SessionView& v) const { return {camera, *v.patch, v.probe.matrix(), true}; }
};

}  // namespace echosim::runner

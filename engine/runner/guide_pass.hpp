// Practice guides (issue 32, "the 3D view helps"): the vessels' course and the image plane drawn
// see-through over the leg, as an anatomy atlas shows what lies under the skin. A trainee learning
// the exam sees where the deep vein and its artery run from the groin to behind the knee, and
// where the probe's image plane cuts them, so the image on the right can be read against the leg
// on the left. A frame pass of the scene's area at PassPlace::after_scene (runner/frame.hpp), after
// the leg and the probe: no depth test (the vessels lie inside the leg and show through it), blended
// "over" with the guide's opacity. Shown or hidden from frame to frame (GuideSwitch: the driver's
// thread, the only one that sets it and records frames).
//
// The vessels are tubes around centrelines sampled from the case's phantom (course_guides), built
// and uploaded once; the image plane is the probe's: its width along the array, its depth down the
// beam, moved with the probe each frame.
#pragma once

#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "echo/anatomy.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "runner/frame.hpp"
#include "scene/leg.hpp"

namespace echosim::runner {

// A vessel to draw: its centreline [mm] and radius there [mm], and its colour (display values and
// the opacity).
struct GuideLine {
    std::vector<glm::vec3> centre;
    std::vector<float> radius_mm;
    glm::vec4 colour{1.0f};
};

// The deep vein from above the ligament to the trifurcation and its artery beside it, sampled every
// 5 mm of the course from the phantom of `anatomy` on `leg`; the great saphenous vein too.
std::vector<GuideLine> course_guides(const scene::LegModel& leg, const echo::Anatomy& anatomy);

// Shown or not; shared by the pass and whoever toggles it (the window's key), on the driver thread.
struct GuideSwitch {
    bool shown = false;
};

// The triangles of a tube of `sides` around `line` (positions, and indices three a triangle); a
// line of fewer than two points makes none.
struct TubeMesh {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
};
TubeMesh tube_mesh(const GuideLine& line, int sides = 8);

class GuidePass final : public SessionPass {
public:
    GuidePass(const PassSetup& setup, std::vector<GuideLine> vessels, std::shared_ptr<const GuideSwitch> shown);
    ~GuidePass() override;

    const char* name() const override { return "practice guides"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::color_attachment(gpu::TargetLoad::load); }
    void set(const session::SessionView& state, VkExtent2D extent) override;
    void record(const gpu::PassContext& frame) override;

private:
    struct Drawn {
        gpu::Buffer vertices, indices;
        std::uint32_t index_count = 0;
        glm::vec4 colour{1.0f};
    };
    const gpu::Context& ctx_;
    const DefaultScene& scene_;
    const image::EchoImageGpu& echo_image_;  // its plane() the displayed image's
    std::shared_ptr<const GuideSwitch> shown_;
    gpu::Pipeline pipeline_;
    std::vector<Drawn> vessels_;
    Drawn plane_;
    glm::mat4 probe_to_world_{1.0f};
};

// The factory of a frame's guide pass (runner/frame.hpp), at PassPlace::after_scene.
PassFactory guide_pass_factory(std::vector<GuideLine> vessels, std::shared_ptr<const GuideSwitch> shown);

}  // namespace echosim::runner

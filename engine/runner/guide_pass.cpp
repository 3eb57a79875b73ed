#include "runner/guide_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "echo/phantom.hpp"
#include "echo/vein_course.hpp"
#include "echosim_graphics_shaders.hpp"
#include "guide_bindings.h"
#include "render/graphics_pipeline.hpp"
#include "render/target_rect.hpp"

namespace echosim::runner {
namespace {

using guide_bindings::GuidePush;

// display colours and opacities: the veins blue, the arteries red, the image plane a pale amber
constexpr glm::vec4 kVein{0.30f, 0.55f, 1.00f, 0.55f};
constexpr glm::vec4 kArtery{1.00f, 0.30f, 0.25f, 0.50f};
constexpr glm::vec4 kPlane{1.00f, 0.85f, 0.35f, 0.30f};
constexpr double kStepCm = 0.5;

template <typename T>
std::span<const std::byte> bytes_of(const std::vector<T>& v)
{
    return std::as_bytes(std::span(v));
}

VkPipeline make_guide_pipeline(VkDevice device, VkPipelineLayout layout, VkFormat color_format)
{
    static constexpr VkVertexInputBindingDescription binding{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX};
    static constexpr VkVertexInputAttributeDescription position{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
    const std::array<VkBool32, 1> constants{gpu::is_srgb(color_format) ? VK_TRUE : VK_FALSE};  // TARGET_ENCODES
    render::GraphicsPipelineDesc desc;
    desc.name = "practice guides";
    desc.vertex_spirv = shaders::guide_vert;
    desc.fragment_spirv = shaders::guide_frag;
    desc.vertex_bindings = std::span(&binding, 1);
    desc.vertex_attributes = std::span(&position, 1);
    desc.color_format = color_format;
    desc.blend = true;
    desc.constants = constants;
    return render::create_graphics_pipeline(device, layout, desc);
}

}  // namespace

std::vector<GuideLine> course_guides(const scene::LegModel& leg, const echo::Anatomy& anatomy)
{
    const echo::Phantom phantom(leg, anatomy);
    GuideLine vein{{}, {}, kVein}, artery{{}, {}, kArtery}, gsv{{}, {}, kVein};
    for (double s = echo::kDeepVeinFrom_cm; s <= echo::kTrifurcation_cm + 1e-9; s += kStepCm) {
        const echo::VesselSection v = phantom.vein(echo::VeinSegment::fv, s);
        vein.centre.emplace_back(v.centre);
        vein.radius_mm.push_back(float(v.lumen_radius + v.wall));
        if (const std::optional<echo::VesselSection> a = phantom.artery(echo::VeinSegment::fv, s)) {
            artery.centre.emplace_back(a->centre);
            artery.radius_mm.push_back(float(a->lumen_radius + a->wall));
        }
    }
    for (double s = 0.0; s <= echo::kGsvModelled_cm + 1e-9; s += kStepCm) {
        if (!phantom.modelled(echo::VeinSegment::gsv, s)) continue;
        const echo::VesselSection v = phantom.vein(echo::VeinSegment::gsv, s);
        gsv.centre.emplace_back(v.centre);
        gsv.radius_mm.push_back(float(v.lumen_radius + v.wall));
    }
    std::vector<GuideLine> out;
    for (GuideLine* l : {&vein, &artery, &gsv})
        if (l->centre.size() >= 2) out.push_back(std::move(*l));
    return out;
}

TubeMesh tube_mesh(const GuideLine& line, int sides)
{
    TubeMesh m;
    const std::size_t n = std::min(line.centre.size(), line.radius_mm.size());
    if (n < 2 || sides < 3) return m;
    glm::vec3 normal(0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 tangent = glm::normalize(line.centre[std::min(i + 1, n - 1)] - line.centre[i > 0 ? i - 1 : 0]);
        // a frame carried along the line (no twist where it bends): the last normal made square to
        // the new tangent, or any square one to start
        if (i == 0) normal = std::abs(tangent.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        normal = glm::normalize(normal - glm::dot(normal, tangent) * tangent);
        const glm::vec3 binormal = glm::cross(tangent, normal);
        for (int k = 0; k < sides; ++k) {
            const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(sides);
            m.positions.push_back(line.centre[i] + line.radius_mm[i] * (std::cos(a) * normal + std::sin(a) * binormal));
        }
    }
    for (std::uint32_t i = 0; i + 1 < std::uint32_t(n); ++i)
        for (std::uint32_t k = 0; k < std::uint32_t(sides); ++k) {
            const std::uint32_t s = std::uint32_t(sides), k1 = (k + 1) % s;
            const std::uint32_t a = i * s + k, b = i * s + k1, c = (i + 1) * s + k, d = (i + 1) * s + k1;
            m.indices.insert(m.indices.end(), {a, b, c, c, b, d});
        }
    return m;
}

GuidePass::GuidePass(const PassSetup& setup, std::vector<GuideLine> vessels, std::shared_ptr<const GuideSwitch> shown)
    : ctx_(setup.ctx), scene_(setup.scene), echo_image_(setup.echo_image), shown_(std::move(shown)),
      pipeline_(setup.ctx.device(), VK_NULL_HANDLE, {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(GuidePush)},
                "practice guides", [&](VkPipelineLayout layout) { return make_guide_pipeline(setup.ctx.device(), layout, setup.format); })
{
    if (!shown_) throw std::invalid_argument("practice guides: no switch to show them by");
    const auto upload = [&](const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices, const glm::vec4& colour) {
        Drawn d;
        d.vertices = gpu::upload_buffer(setup.commands, bytes_of(positions), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        d.indices = gpu::upload_buffer(setup.commands, bytes_of(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        d.index_count = std::uint32_t(indices.size());
        d.colour = colour;
        return d;
    };
    for (const GuideLine& line : vessels) {
        const TubeMesh m = tube_mesh(line);
        if (!m.indices.empty()) vessels_.push_back(upload(m.positions, m.indices, line.colour));
    }
    // the image plane in the probe's frame: across the array (x), down the beam (y) from the face,
    // a millimetre deep: drawn scaled to the displayed image's depth
    const float w = float(echo_image_.plane().width_mm / 2);
    plane_ = upload({{-w, 0.0f, 0.0f}, {w, 0.0f, 0.0f}, {-w, 1.0f, 0.0f}, {w, 1.0f, 0.0f}}, {0, 1, 2, 2, 1, 3}, kPlane);
}

// frames in flight may still use the pipeline and the buffers (gpu/frame.hpp, "Lifetime")
GuidePass::~GuidePass() { ctx_.wait_idle(); }

void GuidePass::set(const session::SessionView& state, VkExtent2D) { probe_to_world_ = state.probe.matrix(); }

void GuidePass::record(const gpu::PassContext& frame)
{
    if (!shown_->shown) return;
    const echo::ImagePlane& plane = echo_image_.plane();
    const VkRect2D area = render::target_pixels(scene_rect(frame.target.extent, plane), frame.target.extent);
    if (area.extent.width == 0 || area.extent.height == 0) return;

    render::begin_rendering_over(frame.cmd, frame.target.view, area, target_use().attachment_load_op());
    vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.handle());
    const glm::mat4 view_proj = scene_.camera.projection(float(area.extent.width) / float(area.extent.height)) * scene_.camera.view();
    const auto draw = [&](const Drawn& d, const glm::mat4& model) {
        const GuidePush push{view_proj * model, d.colour};
        vkCmdPushConstants(frame.cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
        const VkDeviceSize offset = 0;
        const VkBuffer vertices = d.vertices.handle();
        vkCmdBindVertexBuffers(frame.cmd, 0, 1, &vertices, &offset);
        vkCmdBindIndexBuffer(frame.cmd, d.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(frame.cmd, d.index_count, 1, 0, 0, 0);
    };
    for (const Drawn& d : vessels_) draw(d, glm::mat4(1.0f));
    draw(plane_, glm::scale(probe_to_world_, glm::vec3(1.0f, float(plane.depth_mm), 1.0f)));
    vkCmdEndRendering(frame.cmd);
}

PassFactory guide_pass_factory(std::vector<GuideLine> vessels, std::shared_ptr<const GuideSwitch> shown)
{
    return {PassPlace::after_scene, [vessels = std::move(vessels), shown = std::move(shown)](const PassSetup& setup) {
                return std::make_unique<GuidePass>(setup, vessels, shown);
            }};
}

}  // namespace echosim::runner

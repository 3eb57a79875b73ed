#include "app/session_frame.hpp"

#include <algorithm>

namespace echosim::app {

render::TargetRect echo_panel_rect(VkExtent2D frame, const echo::ImagePlane& plane)
{
    const float aspect = float(plane.width_mm / plane.depth_mm) * float(frame.height) / float(std::max(frame.width, 1u));
    const float width = std::min(aspect, 0.5f);
    const float height = width / aspect;
    return {1.0f - width, 0.5f * (1.0f - height), width, height};
}

SessionFrame::SessionFrame(const gpu::Context& ctx, gpu::CommandPool& commands, VkFormat format, const DefaultScene& scene,
                           const VolumePair& volumes)
    : scene_pass_(ctx, commands, format, scene.meshes()),
      echo_image_(ctx, std::make_shared<const image::EchoVolumeGpu>(commands, *volumes.volume, volumes.labels.get()),
                  scene.session.image_plane(), scene.session.patient()),
      smooth_(ctx, gpu::Filter::linear), panel_(ctx, format, {}), echo_pass_(echo_image_, panel_, smooth_),
      passes_{&scene_pass_, &echo_pass_, &panel_}
{
}

void SessionFrame::set(const DefaultScene& scene, const session::SessionView& state, VkExtent2D extent)
{
    scene_pass_.set_view(scene.frame_view(state));
    echo_pass_.set_frame(*state.echo);
    const render::TargetRect panel = echo_panel_rect(extent, scene.session.image_plane());
    panel_.set_rect(panel);
    scene_pass_.set_area({0.0f, 0.0f, panel.x, 1.0f});
}

}  // namespace echosim::app

#include "runner/frame.hpp"

#include <algorithm>
#include <stdexcept>

namespace echosim::runner {

render::TargetRect echo_panel_rect(VkExtent2D frame, const echo::ImagePlane& plane)
{
    const float aspect = float(plane.width_mm / plane.depth_mm) * float(frame.height) / float(std::max(frame.width, 1u));
    const float width = std::min(aspect, 0.5f);
    const float height = width / aspect;
    return {1.0f - width, 0.5f * (1.0f - height), width, height};
}

render::TargetRect scene_rect(VkExtent2D frame, const echo::ImagePlane& plane)
{
    return {0.0f, 0.0f, echo_panel_rect(frame, plane).x, 1.0f};
}

SimulatorFrame::SimulatorFrame(const gpu::Context& ctx, gpu::CommandPool& commands, VkFormat format, const DefaultScene& scene,
                               const io::Volume& volume, const io::Volume* labels, std::span<const PassFactory> extra, echo::Imaging imaging)
    : scene_pass_(ctx, commands, format, scene.meshes()),
      echo_image_(ctx,
                  std::make_shared<const image::EchoVolumeGpu>(
                      commands, volume, labels, image::GreyLayout::best,
                      imaging == echo::Imaging::generative ? image::LabelTexels::make : image::LabelTexels::none),
                  scene.session.image_plane(), scene.session.patient(), image::DeformReads::best, imaging),
      smooth_(ctx, gpu::Filter::linear), panel_(ctx, format, {}), echo_pass_(echo_image_, panel_, smooth_), cue_pass_(commands, format),
      commands_(commands), drawn_window_(scene.session.window_serial())
{
    const PassSetup setup{ctx, commands, format, scene, panel_, echo_image_};
    std::vector<std::pair<PassPlace, gpu::FramePass*>> made;
    for (const PassFactory& f : extra) {
        if (!f.make) throw std::invalid_argument("frame: a configuration's pass has no factory");
        extra_.push_back(f.make(setup));
        if (!extra_.back()) throw std::invalid_argument("frame: a configuration's pass factory made no pass");
        made.emplace_back(f.place, extra_.back().get());
        if (auto* follows = dynamic_cast<SessionPass*>(extra_.back().get())) following_.push_back(follows);
    }
    const auto add = [&](PassPlace place) {
        for (const auto& [p, pass] : made)
            if (p == place) order_.push_back(pass);
    };
    order_.push_back(&scene_pass_);
    add(PassPlace::after_scene);
    order_.push_back(&echo_pass_);
    add(PassPlace::image);
    order_.push_back(&panel_);
    order_.push_back(&cue_pass_);
    add(PassPlace::overlay);
    passes_.emplace(std::span<gpu::FramePass* const>(order_));
}

std::vector<std::string> SimulatorFrame::pass_names() const
{
    std::vector<std::string> names;
    for (const gpu::FramePass* p : order_) names.emplace_back(p->name());
    return names;
}

void SimulatorFrame::set(const DefaultScene& scene, const session::SessionView& state, VkExtent2D extent)
{
    // the exam window moved (a lifted probe's move: rare): the leg with its hole where the window
    // is now, and the window's patch, uploaded again before the view that draws them
    if (state.window_serial != drawn_window_) {
        scene_pass_.replace_leg(commands_, scene.session.leg().static_mesh(), scene.session.leg().patch().rest);
        drawn_window_ = state.window_serial;
    }
    scene_pass_.set_view(scene.frame_view(state));
    echo_pass_.set_frame(*state.echo);
    // the displayed plane: the session's, at the depth the scanner's control set
    const echo::ImagePlane& plane = echo_image_.plane();
    const render::TargetRect panel = echo_panel_rect(extent, plane);
    panel_.set_rect(panel);
    scene_pass_.set_area(scene_rect(extent, plane));
    // frozen, the image and its cue stay those of the frame it was frozen on
    const ImageCue cue = volume_pending_      ? ImageCue::volume_pending
                         : echo_pass_.frozen() ? cue_pass_.cue()
                                               : image_cue(*state.echo, plane, echo_image_.volume_grid());
    cue_pass_.set(cue, panel, extent);
    for (SessionPass* p : following_) p->set(state, extent);
}

}  // namespace echosim::runner

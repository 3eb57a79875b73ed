#include "app/headless.hpp"

#include "gpu/offscreen.hpp"
#include "render/scene_pass.hpp"

namespace echosim::app {

HeadlessFrame render_headless(const gpu::ContextOptions& options, const render::SceneMeshes& meshes, const render::FrameView& view,
                              std::uint32_t width, std::uint32_t height)
{
    HeadlessFrame frame;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(options);
        messages = ctx.validation_counter();
        frame.device = ctx.device_name();
        gpu::CommandPool commands(ctx);  // this thread's
        gpu::OffscreenPresenter presenter(commands, {width, height});
        render::ScenePass scene_pass(ctx, commands, presenter.format(), meshes);
        scene_pass.set_view(view);
        presenter.render({&scene_pass}, &frame.image);
    }
    // read after the device is gone: leaks are reported while it is destroyed
    frame.validation_messages = messages->load();
    return frame;
}

}  // namespace echosim::app

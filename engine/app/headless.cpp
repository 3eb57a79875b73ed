#include "app/headless.hpp"

#include "gpu/offscreen.hpp"

namespace echosim::app {

HeadlessFrame render_headless(const gpu::ContextOptions& options, const gpu::SceneMeshes& meshes, const gpu::FrameView& view,
                              std::uint32_t width, std::uint32_t height)
{
    HeadlessFrame frame;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(options);
        messages = ctx.validation_counter();
        frame.device = ctx.device_name();
        gpu::OffscreenPresenter presenter(ctx, {width, height});
        gpu::Renderer renderer(ctx, gpu::OffscreenPresenter::kFormat, meshes);
        presenter.render(renderer, view, &frame.image);
    }
    // read after the device is gone: leaks are reported while it is destroyed
    frame.validation_messages = messages->load();
    return frame;
}

}  // namespace echosim::app

// The live link end to end, as `echosim run --igtl` wires it: the window's image pass with read-back
// on, frames drawn through a presenter (offscreen here, on lavapipe with validation on), each read
// back a slot later and published; a client written with the OpenIGTLink library receives the image
// and finds the very pixels the GPU made for that input, placed where that input's probe was.
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "app/live_link.hpp"
#include "echo/echo_test_volumes.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/offscreen.hpp"
#include "igtl/igtl_client.hpp"
#include "igtl/server.hpp"
#include "image/echo_image_gpu.hpp"
#include "render/image_panel_pass.hpp"
#include "runner/echo_image_pass.hpp"
#include "runner/runner.hpp"
#include "session/session.hpp"
#include "test_gpu.hpp"

namespace echosim::igtl {
namespace {

// The frame's background (where the window draws the scene): the target cleared by a transfer.
struct ClearPass final : gpu::FramePass {
    const char* name() const override { return "clear"; }
    gpu::TargetUse target_use() const override
    {
        return {{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT}, gpu::TargetLoad::clear};
    }
    void record(const gpu::PassContext& frame) override
    {
        const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(frame.cmd, frame.target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &all);
    }
};

TEST(IgtlLiveLink, PublishesTheImageTheGpuDrewWhereItsProbeWas)
{
    session::Session s;
    const scene::LegModel leg;
    const test::LabelledVolume v = test::phantom_volume(leg, echo::Case::healthy, s.probe().rest, 0.5);
    s.press_and_settle(s.probe().rest, 8.0);
    const echo::EchoFrame pressed = *s.view().echo;
    const echo::ImagePlane& plane = s.image_plane();

    ServerOptions options;
    options.port = 0;  // on the loopback interface, the default
    Server server(options);
    test::IgtlClient client(server.port());
    ASSERT_TRUE(client.ok());

    std::vector<std::uint32_t> drawn;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        gpu::CommandPool pool(ctx);
        const auto volume = std::make_shared<const image::EchoVolumeGpu>(pool, v.grey, &v.labels);
        image::EchoImageGpu pipeline(ctx, volume, plane, s.patient());
        gpu::OffscreenPresenter presenter(pool, {96, 64});
        render::ImagePanelPass panel(ctx, presenter.format(), {});
        const gpu::Sampler nearest(ctx, gpu::Filter::nearest);
        runner::EchoImagePass pass(pipeline, panel, nearest);
        LiveFrame live;
        pass.enable_readback(ctx, [&](const echo::EchoFrame& frame, const echo::ImagePlane& drawn_in, std::span<const std::uint8_t> grey,
                                      double wall_clock_s) {
            app::fill_live_frame(live, drawn_in, frame, grey, wall_clock_s);
            server.publish(live);
        });
        ClearPass clear;
        const gpu::FramePasses passes{&clear, &pass, &panel};
        pass.set_frame(pressed);
        // a frame is handed over when its slot comes round again: after kFramesInFlight + 1 frames, the first
        for (int i = 0; i < gpu::kFramesInFlight; ++i) presenter.render(passes, nullptr);
        EXPECT_EQ(server.stats().frames_published, 0);
        presenter.render(passes, nullptr);
        EXPECT_EQ(server.stats().frames_published, 1);
        // what the same GPU makes of the same input, waited for
        drawn = pipeline.render(pool, pressed).rgba;
    }
    EXPECT_EQ(messages->load(), 0u);

    test::IgtlMessage image, probe;
    ASSERT_TRUE(client.receive(image));
    ASSERT_TRUE(client.receive(probe));
    ASSERT_EQ(image.name, kImageName);
    ASSERT_EQ(probe.name, kProbeToReferenceName);
    int size[3];
    image.image->GetDimensions(size);
    ASSERT_EQ(size[0], int(plane.columns));
    ASSERT_EQ(size[1], int(plane.rows));
    ASSERT_EQ(drawn.size(), plane.pixels());
    const auto* pixels = static_cast<const std::uint8_t*>(image.image->GetScalarPointer());
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < drawn.size(); ++i) wrong += pixels[i] != (drawn[i] & 0xffu);
    EXPECT_EQ(wrong, 0u) << "of " << drawn.size() << " pixels";
    // not a blank image: the phantom's tissue shows
    std::size_t lit = 0;
    for (std::size_t i = 0; i < drawn.size(); ++i) lit += pixels[i] > 20;
    EXPECT_GT(lit, drawn.size() / 4);

    // the probe of that input, in RAS
    ::igtl::Matrix4x4 m;
    probe.transform->GetMatrix(m);
    EXPECT_NEAR(m[0][3], -pressed.face.position.x, 1e-3);
    EXPECT_NEAR(m[1][3], -pressed.face.position.y, 1e-3);
    EXPECT_NEAR(m[2][3], pressed.face.position.z, 1e-3);
    const glm::vec3 beam = pressed.face.axis_y();
    EXPECT_NEAR(m[0][1], -beam.x, 1e-5);
    EXPECT_NEAR(m[1][1], -beam.y, 1e-5);
    EXPECT_NEAR(m[2][1], beam.z, 1e-5);
}

// `echosim run --igtl` wires the link as an observer of the runner (app/live_link.hpp): every frame
// the runner draws is read back a slot later and published; the client receives the image.
TEST(IgtlLiveLink, TheRunnersObserverPublishesTheFramesItDraws)
{
    const scene::LegModel leg;
    const test::LabelledVolume v = test::phantom_volume(leg, echo::Case::healthy, leg.probe_rest_pose(0.5f, 0.5f), 0.6);
    ServerOptions options;
    options.port = 0;
    Server server(options);
    test::IgtlClient client(server.port());
    ASSERT_TRUE(client.ok());
    runner::RunnerConfig c;
    c.name = "live link test";
    c.output = runner::Output::offscreen;
    c.extent = {96, 64};
    c.gpu = test::lavapipe_options();
    c.volume = std::make_shared<const io::Volume>(v.grey);
    c.labels = std::make_shared<const io::Volume>(v.labels);
    c.max_steps = gpu::kFramesInFlight + 3;
    c.observers.push_back(std::make_shared<app::LiveLink>(server, "test: "));
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner r(std::move(c));
        messages = r.validation_counter();
        r.run();
        EXPECT_EQ(r.frames(), gpu::kFramesInFlight + 3);
    }
    // a frame is handed over when its slot comes round again: all but the last kFramesInFlight
    EXPECT_EQ(server.stats().frames_published, 3);
    EXPECT_EQ(messages->load(), 0u);
    test::IgtlMessage image;
    ASSERT_TRUE(client.receive(image));
    EXPECT_EQ(image.name, kImageName);
}

}  // namespace
}  // namespace echosim::igtl

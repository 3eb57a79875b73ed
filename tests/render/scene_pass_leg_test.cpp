// ScenePass::replace_leg: when the exam window moves (session/session.hpp), the pass draws the leg
// with its hole where the window is now, as a pass made for that leg would.
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

#include "app/default_scene.hpp"
#include "gpu/offscreen.hpp"
#include "render/scene_pass.hpp"
#include "test_gpu.hpp"

namespace echosim::render {
namespace {

constexpr std::uint32_t kWidth = 320, kHeight = 240;

TEST(ScenePassLeg, AMovedWindowIsDrawnAsAPassMadeForItDrawsIt)
{
    app::DefaultScene scene;
    scene.camera.target = {-90.0f, -20.0f, -220.0f};  // the thigh from the groin to the canal
    scene.camera.distance = 700.0f;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        gpu::Context ctx(test::lavapipe_options());
        messages = ctx.validation_counter();
        gpu::CommandPool commands(ctx);
        gpu::OffscreenPresenter presenter(commands, {kWidth, kHeight});
        ScenePass pass(ctx, commands, presenter.format(), scene.meshes());
        auto draw = [&](ScenePass& p) {
            FrameView view = scene.frame_view();
            view.show_probe = false;
            p.set_view(view);
            io::RgbaImage img;
            presenter.render({&p}, &img);
            return img;
        };
        const io::RgbaImage home = draw(pass);

        const scene::LegModel& leg = scene.session.leg();
        ASSERT_TRUE(scene.session.move_window({leg.limb_t_at_z(-300.0f), leg.patch().centre_theta()}));
        const std::size_t moved_vertices = scene.session.leg().patch().rest.vertices.size();
        FrameView stale = scene.frame_view();
        if (moved_vertices != scene::LegModel{}.patch().rest.vertices.size())
            EXPECT_THROW(pass.set_view(stale), std::invalid_argument) << "the pass still holds the home patch";
        pass.replace_leg(commands, scene.session.leg().static_mesh(), scene.session.leg().patch().rest);
        const io::RgbaImage moved = draw(pass);

        ScenePass fresh(ctx, commands, presenter.format(), scene.meshes());
        const io::RgbaImage expected = draw(fresh);
        EXPECT_EQ(moved.pixels, expected.pixels);
        EXPECT_NE(moved.pixels, home.pixels) << "the glossier window is drawn at the canal now";
    }
    EXPECT_EQ(messages->load(), 0u);
}

}  // namespace
}  // namespace echosim::render

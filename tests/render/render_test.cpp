// Render tests: headless frames of the default scene on lavapipe, against a reference PNG and
// against what the scene must show. Regenerate the references with scripts/update-references.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "app/default_scene.hpp"
#include "app/headless.hpp"
#include "gpu/offscreen.hpp"
#include "render/image_compare.hpp"
#include "render/scene_pass.hpp"
#include "test_gpu.hpp"

namespace echosim {
namespace {

constexpr std::uint32_t kWidth = 480, kHeight = 270;
// lavapipe is deterministic for one Mesa version; the tolerance absorbs rasterisation and
// rounding changes between Mesa releases without letting a moved or missing object through
constexpr test::Tolerance kReferenceTolerance{12, 0.005};

std::filesystem::path reference(const char* name) { return std::filesystem::path(ECHOSIM_REFERENCE_DIR) / name; }

TEST(Render, DefaultViewMatchesReference)
{
    app::DefaultScene scene;
    const app::HeadlessFrame frame = app::render_headless(test::lavapipe_options(), scene.meshes(), scene.frame_view(), kWidth, kHeight);
    EXPECT_EQ(frame.validation_messages, 0u);
    const auto path = reference("default_view.png");
    if (const char* update = std::getenv("ECHOSIM_UPDATE_REFERENCES"); update && *update == '1') {
        io::write_png(path, frame.image);
        GTEST_SKIP() << "reference regenerated: " << path;
    }
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing: run scripts/update-references";
    const auto cmp = test::compare(frame.image, io::read_png(path), kReferenceTolerance.max_channel_diff);
    EXPECT_TRUE(within(cmp, kReferenceTolerance)) << cmp.describe();
}

// Renders the scene several ways in one context, as the window does frame after frame. The
// validation count is read after every GPU object and the device are gone, so leaks count too.
class SceneRender : public testing::Test {
protected:
    struct Gpu {
        gpu::Context ctx;
        gpu::CommandPool commands;
        gpu::OffscreenPresenter presenter;
        render::ScenePass scene_pass;
        gpu::FramePasses passes;
        explicit Gpu(const app::DefaultScene& scene)
            : ctx(test::lavapipe_options()), commands(ctx), presenter(commands, {kWidth, kHeight}),
              scene_pass(ctx, commands, presenter.format(), scene.meshes()), passes{&scene_pass}
        {
        }
    };

    SceneRender() : gpu_(std::make_unique<Gpu>(scene_)), messages_(gpu_->ctx.validation_counter()) {}
    void TearDown() override
    {
        gpu_.reset();
        EXPECT_EQ(messages_->load(), 0u);
    }

    io::RgbaImage draw(const render::FrameView& view)
    {
        io::RgbaImage img;
        gpu_->scene_pass.set_view(view);
        gpu_->presenter.render(gpu_->passes, &img);
        return img;
    }
    // where a world point lands in the image [px]
    glm::vec2 project(glm::vec3 world) const
    {
        glm::vec4 c = scene_.camera.projection(float(kWidth) / float(kHeight)) * scene_.camera.view() * glm::vec4(world, 1);
        c /= c.w;
        return {(c.x * 0.5f + 0.5f) * float(kWidth), (c.y * 0.5f + 0.5f) * float(kHeight)};
    }
    // changed pixels, and how many of them lie within `radius` px of `centre`
    static std::pair<int, int> changes(const io::RgbaImage& a, const io::RgbaImage& b, glm::vec2 centre, float radius)
    {
        int all = 0, near = 0;
        for (std::uint32_t y = 0; y < a.height; ++y)
            for (std::uint32_t x = 0; x < a.width; ++x)
                if (std::memcmp(a.at(x, y), b.at(x, y), 3) != 0) {
                    ++all;
                    near += glm::length(glm::vec2(float(x), float(y)) - centre) < radius;
                }
        return {all, near};
    }
    // the largest difference of one colour channel between the two, over every pixel
    static int largest_change(const io::RgbaImage& a, const io::RgbaImage& b)
    {
        int largest = 0;
        for (std::uint32_t y = 0; y < a.height; ++y)
            for (std::uint32_t x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
        return largest;
    }

    app::DefaultScene scene_;
    std::unique_ptr<Gpu> gpu_;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages_;
};

TEST_F(SceneRender, SameInputSameImage)
{
    const auto a = draw(scene_.frame_view());
    const auto b = draw(scene_.frame_view());
    EXPECT_EQ(a.pixels, b.pixels);
}

TEST_F(SceneRender, ProbeIsDrawnWhereItsPoseSays)
{
    render::FrameView view = scene_.frame_view();
    const auto with = draw(view);
    view.show_probe = false;
    const auto without = draw(view);
    // the probe's body is 190 mm long: around 40 px at this distance and size
    const Pose probe = scene_.session.view().probe;
    const glm::vec2 at = project(probe.position + probe.axis_y() * -60.0f);
    const auto [all, near] = changes(with, without, at, 60.0f);
    EXPECT_GT(all, 150);
    EXPECT_GT(double(near) / all, 0.95) << "the probe was drawn away from its pose";
}

// The probe hidden under the table (as the popliteal fossa's lies under the knee) is seen through
// it: its ghost (ScenePass::kProbeGhostOpacity) changes the pixels where it lies behind, each of
// them a blend, not the probe drawn over the table opaque.
TEST_F(SceneRender, AProbeHiddenUnderTheTableIsSeenThroughIt)
{
    render::FrameView view = scene_.frame_view();
    // 300 mm posterior (+y: down, into the table on which the patient lies), the pose otherwise the same
    view.probe_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 300, 0)) * view.probe_to_world;
    const auto with = draw(view);
    view.show_probe = false;
    const auto without = draw(view);
    const glm::vec2 at = project(glm::vec3(view.probe_to_world * glm::vec4(0, -60, 0, 1)));
    const auto [all, near] = changes(with, without, at, 80.0f);
    EXPECT_GT(all, 150);
    EXPECT_GT(double(near) / all, 0.95) << "the ghost was drawn away from the probe's pose";
    // see-through: no changed pixel is as far from the table's as an opaque probe would put it
    view.probe_to_world = scene_.frame_view().probe_to_world;
    const auto shown = draw(scene_.frame_view());
    view.show_probe = false;
    const auto bare = draw(view);
    EXPECT_LT(largest_change(with, without), largest_change(shown, bare));
}

TEST_F(SceneRender, PatchDeformationIsDrawn)
{
    const auto rest = draw(scene_.frame_view());
    // push the patch's middle 12 mm into the thigh, as the probe will
    const auto& patch = scene_.session.leg().patch();
    std::vector<scene::Vertex> pushed = patch.rest.vertices;
    for (int i = 0; i < patch.rows; ++i)
        for (int j = 0; j < patch.cols; ++j) {
            const float u = float(i) / float(patch.rows - 1) - 0.5f, v = float(j) / float(patch.cols - 1) - 0.5f;
            auto& vert = pushed[std::size_t(i * patch.cols + j)];
            vert.position -= vert.normal * (12.0f * std::max(0.0f, 1.0f - 4.0f * (u * u + v * v)));
        }
    render::FrameView view = scene_.frame_view();
    view.patch_vertices = pushed;
    view.show_probe = false;
    const auto pressed = draw(view);
    view.patch_vertices = patch.rest.vertices;
    const auto rest_no_probe = draw(view);
    const glm::vec2 centre = project(scene_.session.leg().probe_rest_pose(0.5f, 0.5f).position);
    const auto [all, near] = changes(pressed, rest_no_probe, centre, 60.0f);
    EXPECT_GT(all, 50);
    EXPECT_GT(double(near) / all, 0.95);
    EXPECT_NE(rest.pixels, pressed.pixels);
}

TEST_F(SceneRender, DrawsInItsAreaWhatATargetOfThatSizeShows)
{
    // beside a panel on the right half: the left half shows the scene as a target of the left
    // half's size does (same aspect, same framing), the right half only the background
    render::FrameView view = scene_.frame_view();
    gpu_->scene_pass.set_area({0.0f, 0.0f, 0.5f, 1.0f});
    const io::RgbaImage beside = draw(view);
    io::RgbaImage alone;
    {
        gpu::OffscreenPresenter half(gpu_->commands, {kWidth / 2, kHeight});
        gpu_->scene_pass.set_area({});
        half.render(gpu_->passes, &alone);
    }
    ASSERT_EQ(alone.width, kWidth / 2);
    int differ = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = 0; x < kWidth / 2; ++x) differ += std::memcmp(beside.at(x, y), alone.at(x, y), 3) != 0;
    EXPECT_EQ(differ, 0) << "pixels of the left half unlike the scene drawn alone at that size";
    const std::uint8_t* background = beside.at(kWidth - 1, 0);
    int drawn_right = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = kWidth / 2; x < kWidth; ++x) drawn_right += std::memcmp(beside.at(x, y), background, 3) != 0;
    EXPECT_EQ(drawn_right, 0) << "the scene drew outside its area";
    // and the scene is there at all: the leg covers much of the left half
    int drawn_left = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = 0; x < kWidth / 2; ++x) drawn_left += std::memcmp(beside.at(x, y), background, 3) != 0;
    EXPECT_GT(drawn_left, int(kWidth / 2 * kHeight / 4));
}

}  // namespace
}  // namespace echosim

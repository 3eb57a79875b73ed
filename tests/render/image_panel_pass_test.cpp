// Frames of several passes, read back: the scene, then an image panel over it, and a compute pass
// before both filling the panel's image. Each pass's pixels are checked: outside the panel the
// frame is the scene's own, inside it the image's texels. On lavapipe with validation on; the
// count is read after every GPU object and the device are gone.
#include "render/image_panel_pass.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "app/default_scene.hpp"
#include "echosim_test_kernels.hpp"
#include "gpu/command_pool.hpp"
#include "gpu/compute.hpp"
#include "gpu/kernels/pattern_bindings.h"
#include "gpu/kernels/pattern_expected.hpp"
#include "gpu/offscreen.hpp"
#include "render/scene_pass.hpp"
#include "test_gpu.hpp"

namespace echosim::render {
namespace {

constexpr VkExtent2D kTarget{480, 270};
constexpr VkExtent2D kImage{16, 9};
// 0.6 and 0.4 of 480 x 270: x 288..480, y 54..162, so 12 px per texel either way
constexpr TargetRect kRect{0.6f, 0.2f, 0.4f, 0.4f};
constexpr VkRect2D kPixels{{288, 54}, {192, 108}};

using Texel = std::array<std::uint8_t, 4>;

struct PixelCheck {
    int outside_changed = 0;    // pixels outside the panel unlike the scene-only frame
    int inside_wrong = 0;       // pixels inside unlike the texel under them (by more than 1/255)
    int inside_like_scene = 0;  // pixels inside that are the scene's
};

// `frame` against the scene alone and the panel's image (`texel(i, j)`, nearest sampling)
PixelCheck check(const io::RgbaImage& frame, const io::RgbaImage& scene_only, const std::function<Texel(std::uint32_t, std::uint32_t)>& texel)
{
    PixelCheck c;
    const auto x0 = std::uint32_t(kPixels.offset.x), y0 = std::uint32_t(kPixels.offset.y);
    for (std::uint32_t y = 0; y < frame.height; ++y)
        for (std::uint32_t x = 0; x < frame.width; ++x) {
            const std::uint8_t* got = frame.at(x, y);
            const bool inside = x >= x0 && x < x0 + kPixels.extent.width && y >= y0 && y < y0 + kPixels.extent.height;
            if (!inside) {
                c.outside_changed += std::memcmp(got, scene_only.at(x, y), 4) != 0;
                continue;
            }
            c.inside_like_scene += std::memcmp(got, scene_only.at(x, y), 4) == 0;
            const Texel want = texel((x - x0) * kImage.width / kPixels.extent.width, (y - y0) * kImage.height / kPixels.extent.height);
            for (int ch = 0; ch < 4; ++ch)
                if (std::abs(int(got[ch]) - int(want[std::size_t(ch)])) > 1) {
                    ++c.inside_wrong;
                    break;
                }
        }
    return c;
}

TEST(ImagePanel, CoversItsRectangleOfTheTarget)
{
    const VkRect2D r = target_pixels(kRect, kTarget);
    EXPECT_EQ(r.offset.x, kPixels.offset.x);
    EXPECT_EQ(r.offset.y, kPixels.offset.y);
    EXPECT_EQ(r.extent.width, kPixels.extent.width);
    EXPECT_EQ(r.extent.height, kPixels.extent.height);
    // clipped to the target
    const VkRect2D out = target_pixels({0.9f, -0.5f, 0.5f, 1.0f}, {100, 100});
    EXPECT_EQ(out.offset.x, 90);
    EXPECT_EQ(out.offset.y, 0);
    EXPECT_EQ(out.extent.width, 10u);
    EXPECT_EQ(out.extent.height, 50u);
}

// An image of random display values (opaque), and its texels as the check above reads them.
struct RandomImage {
    std::vector<std::uint8_t> bytes;
    explicit RandomImage(std::uint32_t seed) : bytes(std::size_t(kImage.width) * kImage.height * 4)
    {
        std::mt19937 rng(seed);
        for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = i % 4 == 3 ? 255 : std::uint8_t(rng() % 256);
    }
    Texel operator()(std::uint32_t i, std::uint32_t j) const
    {
        const std::uint8_t* t = &bytes[(std::size_t(j) * kImage.width + i) * 4];
        return Texel{t[0], t[1], t[2], t[3]};
    }
    gpu::Image upload(gpu::CommandPool& commands, VkFormat format = VK_FORMAT_R8G8B8A8_UNORM) const
    {
        gpu::Image image(commands.context(), kImage, format,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
        gpu::upload_image(commands, image, std::as_bytes(std::span(bytes)));
        return image;
    }
};

// What every frame here is drawn with: lavapipe with validation, this thread's pool, the offscreen
// presenter (which alternates the slots), the scene pass, and the panel over it, sampling nearest
// (the texels as they are). The test reads the validation count after it is gone.
struct PanelGpu {
    gpu::Context ctx{test::lavapipe_options()};
    gpu::CommandPool commands{ctx};
    gpu::OffscreenPresenter presenter;
    const gpu::Sampler nearest{ctx, gpu::Filter::nearest};
    ScenePass scene_pass;
    ImagePanelPass panel{ctx, presenter.format(), kRect};

    explicit PanelGpu(app::DefaultScene& scene, VkFormat target = gpu::OffscreenPresenter::kFormat)
        : presenter(commands, kTarget, target), scene_pass(ctx, commands, presenter.format(), scene.meshes())
    {
        scene_pass.set_view(scene.frame_view());
    }
};

TEST(ImagePanel, ShowsAnUploadedImageOverTheScene)
{
    const RandomImage texel(5);

    app::DefaultScene scene;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    io::RgbaImage scene_only, frames[gpu::kFramesInFlight];
    {
        PanelGpu rig(scene);
        messages = rig.ctx.validation_counter();
        const gpu::Image image = texel.upload(rig.commands);
        rig.panel.show(image, rig.nearest);

        rig.presenter.render(gpu::FramePasses{&rig.scene_pass}, &scene_only);
        const gpu::FramePasses passes{&rig.scene_pass, &rig.panel};
        for (auto& f : frames) rig.presenter.render(passes, &f);  // slot 1, then slot 0
    }
    EXPECT_EQ(messages->load(), 0u);

    for (const auto& f : frames) {
        const PixelCheck c = check(f, scene_only, texel);
        EXPECT_EQ(c.outside_changed, 0) << "the panel drew outside its rectangle, or the scene changed";
        EXPECT_EQ(c.inside_wrong, 0) << "pixels of the panel unlike the image's texels";
        // the scene was there before: the leg and the probe cover the right of the default view
        EXPECT_LT(c.inside_like_scene, int(kPixels.extent.width * kPixels.extent.height) / 50);
    }
}

// The same bytes in an sRGB format, which the sampler decodes, and a target in an sRGB format, which
// encodes what is written (the window's fallback where its surface offers no UNORM format), in each
// pairing: the target shows the image's bytes.
TEST(ImagePanel, ShowsTheImagesBytesWhicheverSideIsSrgb)
{
    const RandomImage texel(11);
    for (const VkFormat target : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB})
        for (const VkFormat image_format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB}) {
            app::DefaultScene scene;
            std::shared_ptr<const std::atomic<std::uint32_t>> messages;
            io::RgbaImage scene_only, frame;
            {
                PanelGpu rig(scene, target);
                messages = rig.ctx.validation_counter();
                const gpu::Image image = texel.upload(rig.commands, image_format);
                rig.panel.show(image, rig.nearest);
                rig.presenter.render(gpu::FramePasses{&rig.scene_pass}, &scene_only);
                rig.presenter.render(gpu::FramePasses{&rig.scene_pass, &rig.panel}, &frame);
            }
            EXPECT_EQ(messages->load(), 0u);
            const PixelCheck c = check(frame, scene_only, texel);
            const std::string pairing = "image " + std::to_string(int(image_format)) + " on target " + std::to_string(int(target));
            EXPECT_EQ(c.outside_changed, 0) << pairing;
            EXPECT_EQ(c.inside_wrong, 0) << "pixels of the panel unlike the image's bytes: " << pairing;
        }
}

// The scene encoded by its shaders (per vertex for the matte meshes, interpolated between display
// values) against the scene an sRGB target encodes per pixel: the same picture, to a level.
TEST(ImagePanel, TheSceneShaderEncodedMatchesTheSrgbTargets)
{
    app::DefaultScene scene;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    io::RgbaImage encoded, by_target;
    {
        PanelGpu unorm(scene, VK_FORMAT_R8G8B8A8_UNORM);
        messages = unorm.ctx.validation_counter();
        unorm.presenter.render(gpu::FramePasses{&unorm.scene_pass}, &encoded);
    }
    EXPECT_EQ(messages->load(), 0u);
    {
        PanelGpu srgb(scene, VK_FORMAT_R8G8B8A8_SRGB);
        messages = srgb.ctx.validation_counter();
        srgb.presenter.render(gpu::FramePasses{&srgb.scene_pass}, &by_target);
    }
    EXPECT_EQ(messages->load(), 0u);
    ASSERT_EQ(encoded.pixels.size(), by_target.pixels.size());
    int worst = 0, off_by_more_than_one = 0;
    for (std::size_t i = 0; i < encoded.pixels.size(); ++i) {
        const int d = std::abs(int(encoded.pixels[i]) - int(by_target.pixels[i]));
        worst = std::max(worst, d);
        off_by_more_than_one += d > 1;
    }
    EXPECT_LE(worst, 2);
    EXPECT_LT(off_by_more_than_one, int(encoded.pixels.size()) / 1000) << "worst " << worst;
}

TEST(ImagePanel, EachFrameShowsTheImageShownBeforeIt)
{
    // the offscreen presenter alternates the slots: a slot last recorded with another image must
    // be re-pointed when it is recorded again
    const RandomImage texels[3] = {RandomImage(21), RandomImage(22), RandomImage(23)};
    constexpr int kNone = -1;
    // what is shown before each frame (kNone: show() not called), and what the frame must show
    const int show[] = {kNone, 0, 1, kNone, 2, 0, kNone, kNone, 1};
    const int expect[] = {kNone, 0, 1, 1, 2, 0, 0, 0, 1};

    app::DefaultScene scene;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    io::RgbaImage scene_only, frames[std::size(show)];
    {
        PanelGpu rig(scene);
        messages = rig.ctx.validation_counter();
        std::vector<gpu::Image> images;
        for (const RandomImage& t : texels) images.push_back(t.upload(rig.commands));

        rig.presenter.render(gpu::FramePasses{&rig.scene_pass}, &scene_only);
        const gpu::FramePasses passes{&rig.scene_pass, &rig.panel};
        for (std::size_t f = 0; f < std::size(show); ++f) {
            if (show[f] != kNone) rig.panel.show(images[std::size_t(show[f])], rig.nearest);
            rig.presenter.render(passes, &frames[f]);
        }
    }
    EXPECT_EQ(messages->load(), 0u);

    for (std::size_t f = 0; f < std::size(show); ++f) {
        if (expect[f] == kNone) {
            EXPECT_EQ(frames[f].pixels, scene_only.pixels) << "frame " << f << ": nothing shown yet, the scene alone expected";
            continue;
        }
        const PixelCheck c = check(frames[f], scene_only, texels[expect[f]]);
        EXPECT_EQ(c.outside_changed, 0) << "frame " << f;
        EXPECT_EQ(c.inside_wrong, 0) << "frame " << f << ": not image " << expect[f];
    }
    // the images differ: a frame with a stale binding could not pass the checks above
    EXPECT_NE(texels[0].bytes, texels[1].bytes);
    EXPECT_NE(frames[1].pixels, frames[2].pixels);
}

// A compute pass of the frame: writes this slot's image with the pattern kernel (its seed per slot)
// and leaves it for the panel's fragment shader, which it tells to show it (the panel re-points the
// slot's binding when it records that slot).
class PatternPass final : public gpu::FramePass {
public:
    PatternPass(const gpu::Context& ctx, ImagePanelPass& panel, const gpu::Sampler& sampler)
        : ctx_(ctx), panel_(panel), sampler_(sampler),
          kernel_(ctx, test::kernels::pattern_comp, "pattern.comp", {gpu::BindingKind::storage_image, gpu::BindingKind::uniform_buffer}, 0)
    {
        for (int s = 0; s < gpu::kFramesInFlight; ++s) {
            images_.emplace_back(ctx, kImage, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT);
            const test::kernels::PatternParams params{seed(s), kImage.width, kImage.height, 0};
            params_.emplace_back(ctx, sizeof params, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::host_visible);
            params_.back().write(std::as_bytes(std::span(&params, 1)));
        }
        for (int s = 0; s < gpu::kFramesInFlight; ++s)
            kernel_.bind(s, {gpu::Binding::storage(images_[std::size_t(s)]), gpu::Binding::uniform(params_[std::size_t(s)])});
    }
    // frames in flight may still write the images (gpu/frame.hpp, "Lifetime")
    ~PatternPass() override { ctx_.wait_idle(); }
    PatternPass(const PatternPass&) = delete;
    PatternPass& operator=(const PatternPass&) = delete;
    static std::uint32_t seed(int slot) { return 17u + 100u * std::uint32_t(slot); }

    const char* name() const override { return "pattern (compute)"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::none(); }
    void record(const gpu::PassContext& frame) override
    {
        const VkImage image = images_[std::size_t(frame.slot)].handle();
        // this slot's last frame sampled it; all of it is written anew
        gpu::transition(frame.cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        kernel_.record(frame.cmd, frame.slot, {}, gpu::Groups::cover(kImage, VkExtent2D{PATTERN_GROUP_X, PATTERN_GROUP_Y}));
        gpu::transition(frame.cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        panel_.show(images_[std::size_t(frame.slot)], sampler_);
    }

private:
    const gpu::Context& ctx_;
    ImagePanelPass& panel_;
    const gpu::Sampler& sampler_;
    gpu::ComputeKernel kernel_;
    std::vector<gpu::Image> images_;
    std::vector<gpu::Buffer> params_;
};

TEST(ImagePanel, ShowsWhatAComputePassOfTheSameFrameWrote)
{
    app::DefaultScene scene;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    io::RgbaImage scene_only, frames[2 * gpu::kFramesInFlight];
    {
        PanelGpu rig(scene);
        messages = rig.ctx.validation_counter();
        PatternPass pattern(rig.ctx, rig.panel, rig.nearest);

        rig.presenter.render(gpu::FramePasses{&rig.scene_pass}, &scene_only);  // slot 0
        const gpu::FramePasses passes{&pattern, &rig.scene_pass, &rig.panel};
        for (auto& f : frames) rig.presenter.render(passes, &f);  // slots 1, 0, 1, 0
    }
    EXPECT_EQ(messages->load(), 0u);

    for (std::size_t i = 0; i < std::size(frames); ++i) {
        const int slot = int(i + 1) % gpu::kFramesInFlight;
        const PixelCheck c = check(frames[i], scene_only, [&](std::uint32_t x, std::uint32_t y) {
            return test::pattern_texel(x, y, PatternPass::seed(slot));
        });
        EXPECT_EQ(c.outside_changed, 0) << "frame " << i;
        EXPECT_EQ(c.inside_wrong, 0) << "frame " << i << " (slot " << slot << "): the panel does not show its slot's pattern";
    }
    // the slots' images differ, so each frame showed its own slot's
    EXPECT_NE(frames[0].pixels, frames[1].pixels);
    EXPECT_EQ(frames[0].pixels, frames[2].pixels);
}

}  // namespace
}  // namespace echosim::render

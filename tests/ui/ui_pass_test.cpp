// The UI pass (ui/ui_pass.hpp) in the runner's offscreen frame on lavapipe, validation on (any
// message fails): a panel drawn by the pass changes the frame's pixels where the panel is and
// nowhere else (the frame without the pass read back beside it); a click injected as UiInput (the
// mouse over a button, down one step, up the next) is seen by the UI as the button pressed; the
// keyboard and typed characters reach a text field; a solid background (ui::solid_background,
// ui::solid_rect) is one colour under the widgets, the scene not showing through; a hidden pass
// leaves the frame as without it.
#include <cstdint>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <imgui.h>

#include "echo/echo_test_volumes.hpp"
#include "runner/exam_config.hpp"
#include "test_gpu.hpp"
#include "ui/ui_pass.hpp"

namespace echosim {
namespace {

struct Volumes {
    std::shared_ptr<const io::Volume> grey, labels;
};
const Volumes& small_volume()
{
    static const Volumes v = [] {
        const scene::LegModel leg;
        test::LabelledVolume lv = test::phantom_volume(leg, echo::Case::healthy, leg.probe_rest_pose(0.5f, 0.5f), 0.6);
        return Volumes{std::make_shared<const io::Volume>(std::move(lv.grey)), std::make_shared<const io::Volume>(std::move(lv.labels))};
    }();
    return v;
}

// Reads back every frame; the last one kept.
struct LastFrame final : runner::Observer {
    io::RgbaImage pixels;
    void on_step(runner::StepContext& step) override { step.want_frame(true); }
    void on_frame(const runner::FrameContext& f) override
    {
        if (f.pixels) pixels = *f.pixels;
    }
};

// A script of UiInput, one a step, fed to the pass.
struct Script final : runner::Input {
    std::vector<ui::UiInput> steps;
    ui::UiPass** pass = nullptr;
    std::size_t next = 0;
    bool poll(runner::Runner&, double) override
    {
        if (*pass && next < steps.size()) (*pass)->feed(steps[next]);
        ++next;
        return true;
    }
};

// What the test's UI saw.
struct Seen {
    int clicks = 0;
    char name[64] = "";
};

// the panel: a window at (40, 30), 300 x 200 px, a button and a text field
constexpr float kPanelX = 40, kPanelY = 30, kPanelW = 300, kPanelH = 200;

void draw_panel(Seen& seen)
{
    ImGui::SetNextWindowPos(ImVec2(kPanelX, kPanelY));
    ImGui::SetNextWindowSize(ImVec2(kPanelW, kPanelH));
    ImGui::Begin("test panel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::SetCursorPos(ImVec2(20, 50));
    if (ImGui::Button("press me", ImVec2(160, 40))) ++seen.clicks;
    ImGui::SetCursorPos(ImVec2(20, 120));
    ImGui::SetNextItemWidth(200);
    ImGui::InputText("##name", seen.name, sizeof seen.name);
    ImGui::End();
}

// the panel with a solid background and, under the button's left half, a solid red rectangle
void draw_solid_panel(Seen& seen)
{
    ImGui::SetNextWindowPos(ImVec2(kPanelX, kPanelY));
    ImGui::SetNextWindowSize(ImVec2(kPanelW, kPanelH));
    ImGui::Begin("test panel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBackground);
    ui::solid_background();
    ui::solid_rect(ImVec2(kPanelX + 20, kPanelY + 50), ImVec2(kPanelX + 100, kPanelY + 90), ImVec4(1, 0, 0, 1));
    ImGui::SetCursorPos(ImVec2(20, 50));
    if (ImGui::Button("press me", ImVec2(160, 40))) ++seen.clicks;
    ImGui::End();
}

enum class Panel { plain, solid, hidden };

struct UiRun {
    io::RgbaImage last;
    std::uint32_t messages = 0;
    std::int64_t ui_frames = 0;
};

// `steps` steps of a resting probe at 320 x 240, with the UI pass (and `script`) or without
UiRun run(bool with_ui, int steps, Seen* seen, std::vector<ui::UiInput> script = {}, Panel panel = Panel::plain)
{
    const Volumes& v = small_volume();
    runner::ExamOptions o;
    o.volume = v.grey;
    o.labels = v.labels;
    o.gpu = test::lavapipe_options();
    o.extent = {320, 240};
    o.duration_s = steps / 60.0;
    auto frames = std::make_shared<LastFrame>();
    o.observers.push_back(frames);
    ui::UiPass* pass = nullptr;
    auto input = std::make_shared<Script>();
    input->steps = std::move(script);
    input->pass = &pass;
    o.input = input;
    runner::RunnerConfig config = runner::exam_config(std::move(o));
    if (with_ui)
        config.passes.push_back({runner::PassPlace::overlay, [&](const runner::PassSetup& setup) {
                                     auto p = std::make_unique<ui::UiPass>(setup, ui::UiOptions{.scale = 1.0f});
                                     p->set_draw([seen, panel](const session::SessionView&, VkExtent2D) {
                                         if (panel == Panel::solid) draw_solid_panel(*seen);
                                         else draw_panel(*seen);
                                     });
                                     p->set_shown(panel != Panel::hidden);
                                     pass = p.get();
                                     return p;
                                 }});
    UiRun r;
    std::shared_ptr<const std::atomic<std::uint32_t>> messages;
    {
        runner::Runner runner(std::move(config));
        messages = runner.validation_counter();
        if (with_ui) {
            const std::vector<std::string> names = runner.frame()->pass_names();
            EXPECT_EQ(names.back(), "ui");
        }
        runner.run();
        r.ui_frames = pass ? pass->frames_built() : 0;
    }
    r.last = frames->pixels;
    r.messages = messages->load();
    return r;
}

std::uint32_t pixel(const io::RgbaImage& im, int x, int y)
{
    const std::uint8_t* p = &im.pixels[(std::size_t(y) * im.width + std::size_t(x)) * 4];
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16;
}

TEST(UiPass, DrawsItsPanelWhereItIsAndNothingElse)
{
    Seen seen;
    const UiRun plain = run(false, 3, nullptr);
    const UiRun ui = run(true, 3, &seen);
    EXPECT_EQ(plain.messages, 0u);
    EXPECT_EQ(ui.messages, 0u);
    EXPECT_EQ(ui.ui_frames, 3);
    ASSERT_EQ(plain.last.width, 320u);
    ASSERT_EQ(ui.last.width, 320u);
    ASSERT_EQ(ui.last.height, 240u);
    long inside = 0, inside_changed = 0, outside_changed = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x) {
            const bool in = float(x) >= kPanelX && float(x) < kPanelX + kPanelW && float(y) >= kPanelY && float(y) < kPanelY + kPanelH;
            const bool changed = pixel(plain.last, x, y) != pixel(ui.last, x, y);
            if (in) {
                ++inside;
                inside_changed += changed;
            } else {
                outside_changed += changed;
            }
        }
    // the panel's window is opaque but for its translucent background (ImGui's dark style, alpha
    // 0.94): nearly every pixel under it changes; outside it none does (anti-aliased edges of a
    // window with rounded corners stay inside its rectangle)
    EXPECT_GT(double(inside_changed) / double(inside), 0.95) << inside_changed << " of " << inside;
    EXPECT_EQ(outside_changed, 0);
    // the button's face: ImGui's dark style button colour (66, 150, 250) at alpha 0.40 over the
    // window, a blue well away from the leg's and the panel's greys
    const std::uint32_t face = pixel(ui.last, int(kPanelX + 20 + 80), int(kPanelY + 50 + 8));
    const int r = int(face & 0xff), g = int(face >> 8 & 0xff), b = int(face >> 16 & 0xff);
    EXPECT_GT(b, r + 40) << r << "," << g << "," << b;
}

TEST(UiPass, ASolidBackgroundIsOneColourUnderTheWidgetsAndAHiddenPassLeavesTheFrame)
{
    Seen seen;
    const UiRun plain = run(false, 3, nullptr);
    const UiRun solid = run(true, 3, &seen, {}, Panel::solid);
    const UiRun hidden = run(true, 3, &seen, {}, Panel::hidden);
    EXPECT_EQ(solid.messages, 0u);
    EXPECT_EQ(hidden.messages, 0u);
    ASSERT_EQ(solid.last.width, 320u);
    ASSERT_EQ(hidden.last.width, 320u);
    EXPECT_EQ(hidden.ui_frames, 0);
    EXPECT_EQ(hidden.last.pixels, plain.last.pixels);
    // below the button, inside the window's border: one colour, whatever the scene under it
    const std::uint32_t bg = pixel(solid.last, int(kPanelX + 10), int(kPanelY + 120));
    long below_n = 0, below_changed = 0, other = 0, outside_changed = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x) {
            const bool below = x >= int(kPanelX + 4) && x < int(kPanelX + kPanelW - 4) && y >= int(kPanelY + 100) && y < int(kPanelY + kPanelH - 4);
            const bool in = float(x) >= kPanelX && float(x) < kPanelX + kPanelW && float(y) >= kPanelY && float(y) < kPanelY + kPanelH;
            if (below) {
                ++below_n;
                other += pixel(solid.last, x, y) != bg;
                below_changed += pixel(plain.last, x, y) != pixel(solid.last, x, y);
            }
            if (!in) outside_changed += pixel(plain.last, x, y) != pixel(solid.last, x, y);
        }
    EXPECT_EQ(other, 0);
    EXPECT_GT(double(below_changed) / double(below_n), 0.95) << below_changed << " of " << below_n;
    EXPECT_EQ(outside_changed, 0);
    // the red rectangle under the button's translucent face: red still, blued a little
    const std::uint32_t under = pixel(solid.last, int(kPanelX + 40), int(kPanelY + 58));
    EXPECT_GT(int(under & 0xff), int(under >> 8 & 0xff) + 80) << std::hex << under;
    // beside it the face over the window's background: blue
    const std::uint32_t face = pixel(solid.last, int(kPanelX + 150), int(kPanelY + 58));
    EXPECT_GT(int(face >> 16 & 0xff), int(face & 0xff) + 40) << std::hex << face;
}

TEST(UiPass, AnInjectedClickPressesTheButtonAndTypedKeysReachTheField)
{
    Seen seen;
    ui::UiInput hover;
    hover.mouse_x = kPanelX + 20 + 80;  // the button's middle
    hover.mouse_y = kPanelY + 50 + 20;
    ui::UiInput down = hover;
    down.mouse_down[0] = true;
    ui::UiInput up = hover;
    // then into the text field: a click, "Ada", a backspace, "a"
    ui::UiInput field;
    field.mouse_x = kPanelX + 20 + 50;
    field.mouse_y = kPanelY + 120 + 10;
    ui::UiInput field_down = field;
    field_down.mouse_down[0] = true;
    ui::UiInput typed = field;
    typed.chars = U"Ada";
    ui::UiInput back = field;
    back.pressed = {ui::Key::backspace};
    ui::UiInput more = field;
    more.chars = U"a";
    const UiRun r = run(true, 12, &seen, {hover, hover, down, up, up, field, field_down, field, typed, back, more, field});
    EXPECT_EQ(r.messages, 0u);
    EXPECT_EQ(seen.clicks, 1);
    EXPECT_STREQ(seen.name, "Ada");  // "Ada", backspace: "Ad", "a": "Ada"
}

TEST(UiPass, AClickShorterThanAStepIsNotLost)
{
    Seen seen;
    ui::UiInput hover;
    hover.mouse_x = kPanelX + 100;
    hover.mouse_y = kPanelY + 70;
    ui::UiInput click = hover;
    click.mouse_clicked[0] = true;  // down and up between two polls
    const UiRun r = run(true, 5, &seen, {hover, hover, click, hover, hover});
    EXPECT_EQ(r.messages, 0u);
    EXPECT_EQ(seen.clicks, 1);
}

}  // namespace
}  // namespace echosim

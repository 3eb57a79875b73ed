// The UI pass (issue 32): Dear ImGui drawn over the frame, the last of the runner's passes
// (PassPlace::overlay, runner/frame.hpp).
//
// Debian's Dear ImGui 1.86 (libimgui-dev, its Vulkan back-end compiled in) draws with a pipeline
// made for a VkRenderPass, not for dynamic rendering, so this pass owns one: one colour attachment
// in the presenter's format, loaded (the frame drawn so far stays under the UI) and kept in
// COLOR_ATTACHMENT_OPTIMAL before and after, the layout the pass declares (TargetUse), so the frame
// recorder's barriers stay the only layout changes. Its framebuffers are imageless (Vulkan 1.2,
// enabled by gpu/context.cpp): one per target extent and usage, the frame's view handed in when
// the render pass begins, so a swapchain rebuilt on a resize never leaves a framebuffer holding a
// destroyed view. All are destroyed with the pass, after the device is idle (gpu/frame.hpp).
//
// Each pass owns its ImGui context (fonts, style, the windows' state). ImGui keeps one global: the
// current context pointer (ImGui::GetCurrentContext). Every member of the pass that touches ImGui
// makes its own context current first, and `draw` callbacks run with it current; nothing else is
// global, so two passes (two runners, a test beside an application) coexist on one thread. The
// back-ends keep their state in the context (io.BackendRendererUserData), so they follow it.
//
// One frame of UI:
//   feed(input)  : the step's input (ui/ui_input.hpp), queued: each frame built takes one, in order,
//                  so a press, its release and a typed word arrive as a script wrote them;
//   set(view, e) : (runner, before the frame is drawn) the next queued input given to ImGui (1.86
//                  has no event queue: io.MousePos, io.MouseDown, io.KeysDown, AddInputCharacter),
//                  NewFrame, the owner's draw callback (the trainer's screens), Render;
//   record()     : the draw data into the frame's command buffer, inside the pass's render pass.
// Solid backgrounds: a window begun with ImGuiWindowFlags_NoBackground and then solid_background()
// gets its background as a clear of its rectangle (vkCmdClearAttachments) at the start of the
// pass, under everything ImGui draws, instead of ImGui's triangles. On lavapipe every pixel ImGui
// covers runs its textured, blended fragment shader (some 10 ns a pixel on two loaded cores: the
// start screen's 760x700 window about 5 ms of a 1080p frame, bench/ui_bench.cpp); a clear is a
// fill. Opaque only, and square-cornered.
//
// Fonts are rasterised and uploaded once, at set-up, at the scale asked for (UiOptions::scale: the
// kiosk's monitor content scale), with the style's sizes scaled alike.
//
// Threads: the runner's driver thread (the one recording frames), as every pass.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "runner/frame.hpp"
#include "ui/ui_input.hpp"

struct ImGuiContext;
struct ImFont;
struct ImVec2;
struct ImVec4;

namespace echosim::ui {

struct UiOptions {
    float scale = 1.0f;         // fonts and sizes (1: 16 px text); the kiosk's is its monitor's content scale
    float font_px = 16.0f;      // the body text at scale 1 [px]
    bool load_system_font = true;  // DejaVu Sans (fonts-dejavu-core) when installed, else ImGui's own
};

// The fonts a draw callback may push (ImGui::PushFont).
struct UiFonts {
    ImFont* body = nullptr;
    ImFont* large = nullptr;  // headings (1.6x, bold)
    ImFont* bold = nullptr;   // buttons (1.15x, bold)
};

// Inside a draw callback, right after ImGui::Begin of a window begun with
// ImGuiWindowFlags_NoBackground: the window's background as the style's WindowBg colour, opaque,
// cleared under the UI (above), and its border drawn as ImGui would. Nothing outside a draw callback.
void solid_background();
// A rectangle [px, screen] of `colour` (its alpha ignored: opaque) on the solid background of the
// window being drawn, cleared as it is: in call order, under everything ImGui draws.
void solid_rect(const ImVec2& min, const ImVec2& max, const ImVec4& colour);

class UiPass final : public runner::SessionPass {
public:
    // What the owner draws each frame, with the pass's context current: ImGui calls only.
    using Draw = std::function<void(const session::SessionView& view, VkExtent2D extent)>;

    UiPass(const runner::PassSetup& setup, const UiOptions& options = {});
    ~UiPass() override;
    UiPass(const UiPass&) = delete;
    UiPass& operator=(const UiPass&) = delete;

    void set_draw(Draw draw) { draw_ = std::move(draw); }
    // Hidden, the pass builds and draws nothing (the frame as without it: bench/ui_bench.cpp's
    // baseline); the input queued waits for the frames after it is shown again.
    void set_shown(bool shown) { shown_ = shown; }
    // The step's input, queued for the next frames built (above).
    void feed(const UiInput& input);
    std::size_t queued() const { return queue_.size(); }

    // runner::SessionPass
    void set(const session::SessionView& view, VkExtent2D extent) override;
    const char* name() const override { return "ui"; }
    gpu::TargetUse target_use() const override { return gpu::TargetUse::color_attachment(gpu::TargetLoad::load); }
    void record(const gpu::PassContext& frame) override;

    // Whether ImGui, at the last frame built, had a text field taking the keyboard (the trainer's
    // letter shortcuts stand aside then) or the mouse over one of its windows.
    bool wants_text() const { return wants_text_; }
    bool wants_mouse() const { return wants_mouse_; }
    std::int64_t frames_built() const { return frames_built_; }
    float scale() const { return options_.scale; }
    const UiFonts& fonts() const { return fonts_; }
    ImGuiContext* context() const { return imgui_; }

    // What solid_background() asks for, this frame: a rectangle [px] and its colour.
    struct Backdrop {
        float x0, y0, x1, y1;
        float rgb[3];
    };
    void add_backdrop(const Backdrop& b) { backdrops_.push_back(b); }

private:
    void apply(const UiInput& in, float dt_s);
    VkFramebuffer framebuffer_for(const gpu::FrameTarget& target);

    const gpu::Context& ctx_;
    UiOptions options_;
    VkFormat format_;
    ImGuiContext* imgui_ = nullptr;
    UiFonts fonts_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptors_ = VK_NULL_HANDLE;
    struct Framebuffer {
        VkExtent2D extent;
        VkImageUsageFlags usage;
        VkFramebuffer handle;
    };
    std::vector<Framebuffer> framebuffers_;
    Draw draw_;
    std::deque<UiInput> queue_;
    UiInput current_;           // the mouse as last fed (held between inputs)
    std::vector<int> down_;     // the keys ImGui was told are down, to release them
    bool built_ = false;        // a frame built since the last record: draw data to record
    bool shown_ = true;
    std::vector<Backdrop> backdrops_;  // this frame's, drawn first (solid_background)
    bool wants_text_ = false, wants_mouse_ = false;
    std::int64_t frames_built_ = 0;
    double last_time_s_ = -1;
};

}  // namespace echosim::ui

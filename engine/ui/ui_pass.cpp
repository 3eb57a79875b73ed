#include "ui/ui_pass.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <imgui.h>
#include <backends/imgui_impl_vulkan.h>

#include "gpu/vk_error.hpp"

namespace echosim::ui {
namespace {

// the font when installed (fonts-dejavu-core, scripts/deps); ImGui's own otherwise
constexpr const char* kSystemFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr const char* kSystemBoldFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

// ImGui's back-end reports its Vulkan results here: an error (a buffer it cannot allocate or map,
// a lost device) is thrown as the set-up's errors are; the runner's caller sees it
void check_backend(VkResult result)
{
    if (result < 0) throw gpu::VulkanError(result, "Dear ImGui's Vulkan back-end");
}

// makes `ctx` current for the scope and restores what was current before
class CurrentContext {
public:
    explicit CurrentContext(ImGuiContext* ctx) : previous_(ImGui::GetCurrentContext()) { ImGui::SetCurrentContext(ctx); }
    ~CurrentContext() { ImGui::SetCurrentContext(previous_); }
    CurrentContext(const CurrentContext&) = delete;
    CurrentContext& operator=(const CurrentContext&) = delete;

private:
    ImGuiContext* previous_;
};

ImFont* add_font(ImGuiIO& io, const char* file, float px)
{
    if (file && std::filesystem::exists(file)) {
        ImFontConfig config;
        config.OversampleH = 2;
        config.OversampleV = 2;
        if (ImFont* f = io.Fonts->AddFontFromFileTTF(file, px, &config)) return f;
    }
    ImFontConfig config;
    config.SizePixels = px;
    return io.Fonts->AddFontDefault(&config);
}

}  // namespace

void solid_rect(const ImVec2& a, const ImVec2& b, const ImVec4& c)
{
    auto* pass = static_cast<UiPass*>(ImGui::GetIO().UserData);
    if (!pass) return;
    // within the window's clip rectangle, as ImGui would clip it
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 lo = dl->GetClipRectMin(), hi = dl->GetClipRectMax();
    pass->add_backdrop({std::max(a.x, lo.x), std::max(a.y, lo.y), std::min(b.x, hi.x), std::min(b.y, hi.y), {c.x, c.y, c.z}});
}

void solid_background()
{
    const ImVec2 a = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const ImVec2 b(a.x + size.x, a.y + size.y);
    const ImVec4 c = ImGui::GetStyleColorVec4(ImGuiCol_WindowBg);
    if (auto* pass = static_cast<UiPass*>(ImGui::GetIO().UserData)) pass->add_backdrop({a.x, a.y, b.x, b.y, {c.x, c.y, c.z}});
    // the border ImGuiWindowFlags_NoBackground leaves out; drawn outside the window's clip rectangle
    const float border = ImGui::GetStyle().WindowBorderSize;
    if (border > 0) ImGui::GetForegroundDrawList()->AddRect(a, b, ImGui::GetColorU32(ImGuiCol_Border), 0.0f, 0, border);
}

UiPass::UiPass(const runner::PassSetup& setup, const UiOptions& options) : ctx_(setup.ctx), options_(options), format_(setup.format)
{
    if (!(options_.scale > 0.25f && options_.scale <= 8.0f)) throw std::invalid_argument("ui: scale " + std::to_string(options_.scale) + " outside 0.25..8");
    const VkDevice device = ctx_.device();

    // the render pass: one colour attachment, loaded and stored, in the layout the pass declares
    VkAttachmentDescription color{};
    color.format = format_;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    // the frame recorder's barrier before the pass makes the earlier passes' writes visible; these
    // say the same within the render pass
    VkSubpassDependency deps[2]{};
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &color;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = 2;
    rp.pDependencies = deps;
    gpu::check(vkCreateRenderPass(device, &rp, nullptr, &render_pass_), "vkCreateRenderPass (ui)");

    // the font atlas's one descriptor set
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dp.maxSets = 1;
    dp.poolSizeCount = 1;
    dp.pPoolSizes = &size;
    gpu::check(vkCreateDescriptorPool(device, &dp, nullptr, &descriptors_), "vkCreateDescriptorPool (ui)");

    // the context, its style and fonts at the scale asked for
    imgui_ = ImGui::CreateContext();
    CurrentContext current(imgui_);
    ImGuiIO& io = ImGui::GetIO();
    io.UserData = this;        // solid_background() finds the pass here
    io.IniFilename = nullptr;  // no imgui.ini written into the working folder
    io.LogFilename = nullptr;
    io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;
    io.BackendPlatformName = "echosim ui (UiInput)";
    io.KeyMap[ImGuiKey_Tab] = int(Key::tab);
    io.KeyMap[ImGuiKey_LeftArrow] = int(Key::left);
    io.KeyMap[ImGuiKey_RightArrow] = int(Key::right);
    io.KeyMap[ImGuiKey_UpArrow] = int(Key::up);
    io.KeyMap[ImGuiKey_DownArrow] = int(Key::down);
    io.KeyMap[ImGuiKey_PageUp] = int(Key::page_up);
    io.KeyMap[ImGuiKey_PageDown] = int(Key::page_down);
    io.KeyMap[ImGuiKey_Home] = int(Key::home);
    io.KeyMap[ImGuiKey_End] = int(Key::end);
    io.KeyMap[ImGuiKey_Delete] = int(Key::del);
    io.KeyMap[ImGuiKey_Backspace] = int(Key::backspace);
    io.KeyMap[ImGuiKey_Space] = int(Key::space);
    io.KeyMap[ImGuiKey_Enter] = int(Key::enter);
    io.KeyMap[ImGuiKey_Escape] = int(Key::escape);
    io.KeyMap[ImGuiKey_KeyPadEnter] = int(Key::enter);
    io.KeyMap[ImGuiKey_A] = 'A';
    io.KeyMap[ImGuiKey_C] = 'C';
    io.KeyMap[ImGuiKey_V] = 'V';
    io.KeyMap[ImGuiKey_X] = 'X';
    io.KeyMap[ImGuiKey_Y] = 'Y';
    io.KeyMap[ImGuiKey_Z] = 'Z';
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 6;
    style.FrameRounding = 4;
    style.WindowPadding = ImVec2(12, 12);
    style.FramePadding = ImVec2(8, 5);
    style.ItemSpacing = ImVec2(10, 8);
    style.ScaleAllSizes(options_.scale);
    const float px = options_.font_px * options_.scale;
    fonts_.body = add_font(io, options_.load_system_font ? kSystemFont : nullptr, px);
    fonts_.large = add_font(io, options_.load_system_font ? kSystemBoldFont : nullptr, px * 1.6f);
    fonts_.bold = add_font(io, options_.load_system_font ? kSystemBoldFont : nullptr, px * 1.15f);

    // the back-end: its pipeline made for our render pass; its fonts uploaded once, now
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = ctx_.instance();
    info.PhysicalDevice = ctx_.physical_device();
    info.Device = device;
    info.QueueFamily = ctx_.queue_family();
    vkGetDeviceQueue(device, ctx_.queue_family(), 0, &info.Queue);  // asked for by Init, used only by helpers we do not call
    info.DescriptorPool = descriptors_;
    // its vertex and index buffers rotate over this many frames: more than the frames in flight, so
    // a frame's buffers are rewritten only after the GPU is done with them (gpu/frame.hpp)
    info.MinImageCount = gpu::kFramesInFlight;
    info.ImageCount = gpu::kFramesInFlight + 1;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = check_backend;
    if (!ImGui_ImplVulkan_Init(&info, render_pass_)) throw std::runtime_error("ui: Dear ImGui's Vulkan back-end did not start");
    setup.commands.submit_and_wait([](VkCommandBuffer cmd) {
        if (!ImGui_ImplVulkan_CreateFontsTexture(cmd)) throw std::runtime_error("ui: the font atlas could not be uploaded");
    });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

UiPass::~UiPass()
{
    // frames in flight may still draw with the pipeline, the fonts and the framebuffers
    ctx_.wait_idle();
    {
        CurrentContext current(imgui_);
        ImGui_ImplVulkan_Shutdown();
    }
    ImGui::DestroyContext(imgui_);
    for (const Framebuffer& f : framebuffers_) vkDestroyFramebuffer(ctx_.device(), f.handle, nullptr);
    vkDestroyDescriptorPool(ctx_.device(), descriptors_, nullptr);
    vkDestroyRenderPass(ctx_.device(), render_pass_, nullptr);
}

void UiPass::feed(const UiInput& input)
{
    queue_.push_back(input);
}

void UiPass::apply(const UiInput& in, float dt_s)
{
    ImGuiIO& io = ImGui::GetIO();
    io.DeltaTime = dt_s;
    io.MousePos = in.mouse_x < 0 || in.mouse_y < 0 ? ImVec2(-FLT_MAX, -FLT_MAX) : ImVec2(in.mouse_x, in.mouse_y);
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = in.mouse_down[std::size_t(b)] || in.mouse_clicked[std::size_t(b)];
    io.MouseWheel = in.wheel;
    io.KeyCtrl = in.ctrl;
    io.KeyShift = in.shift;
    io.KeyAlt = in.alt;
    for (int k : down_) io.KeysDown[k] = false;
    down_.clear();
    auto press = [&](Key k) {
        const int i = int(k);
        if (i <= 0 || i >= int(IM_ARRAYSIZE(io.KeysDown))) return;
        io.KeysDown[i] = true;
        down_.push_back(i);
    };
    for (Key k : in.held) press(k);
    for (Key k : in.pressed) press(k);
    for (char32_t c : in.chars) io.AddInputCharacter(static_cast<unsigned int>(c));
}

void UiPass::set(const session::SessionView& view, VkExtent2D extent)
{
    built_ = false;
    if (!shown_) return;
    CurrentContext current(imgui_);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(extent.width), float(extent.height));
    io.DisplayFramebufferScale = ImVec2(1, 1);
    // the session's clock, so a lock-step run builds the same UI frames run after run
    const double dt = last_time_s_ < 0 ? 1.0 / 60.0 : view.time_s - last_time_s_;
    last_time_s_ = view.time_s;
    const float dt_s = float(std::clamp(dt, 1e-4, 1.0));
    if (!queue_.empty()) {
        current_ = std::move(queue_.front());
        queue_.pop_front();
        apply(current_, dt_s);
        // what stays between inputs: the mouse where it was, the buttons as they were; no key, no wheel
        current_.pressed.clear();
        current_.chars.clear();
        current_.wheel = 0;
        current_.mouse_clicked = {};
    } else {
        apply(current_, dt_s);
    }
    backdrops_.clear();
    ImGui_ImplVulkan_NewFrame();
    ImGui::NewFrame();
    if (draw_) draw_(view, extent);
    ImGui::Render();
    wants_text_ = io.WantTextInput;
    wants_mouse_ = io.WantCaptureMouse;
    built_ = true;
    ++frames_built_;
}

VkFramebuffer UiPass::framebuffer_for(const gpu::FrameTarget& target)
{
    for (const Framebuffer& f : framebuffers_)
        if (f.extent.width == target.extent.width && f.extent.height == target.extent.height && f.usage == target.usage) return f.handle;
    VkFramebufferAttachmentImageInfo image{VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENT_IMAGE_INFO};
    image.usage = target.usage;
    image.width = target.extent.width;
    image.height = target.extent.height;
    image.layerCount = 1;
    image.viewFormatCount = 1;
    image.pViewFormats = &format_;
    VkFramebufferAttachmentsCreateInfo attachments{VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENTS_CREATE_INFO};
    attachments.attachmentImageInfoCount = 1;
    attachments.pAttachmentImageInfos = &image;
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.pNext = &attachments;
    info.flags = VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT;
    info.renderPass = render_pass_;
    info.attachmentCount = 1;
    info.width = target.extent.width;
    info.height = target.extent.height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    gpu::check(vkCreateFramebuffer(ctx_.device(), &info, nullptr, &fb), "vkCreateFramebuffer (ui)");
    // a window resized many times keeps a few extents; older ones are dropped only at tear-down
    framebuffers_.push_back({target.extent, target.usage, fb});
    return fb;
}

void UiPass::record(const gpu::PassContext& frame)
{
    if (!built_) return;  // no UI built yet: nothing drawn, the target untouched
    if (frame.target.format != format_)
        throw std::logic_error("ui: the target's format " + std::to_string(int(frame.target.format)) + " is not the one the pass was made for");
    CurrentContext current(imgui_);
    ImDrawData* data = ImGui::GetDrawData();
    if (!data || data->CmdListsCount == 0) return;
    const VkImageView view = frame.target.view;
    VkRenderPassAttachmentBeginInfo views{VK_STRUCTURE_TYPE_RENDER_PASS_ATTACHMENT_BEGIN_INFO};
    views.attachmentCount = 1;
    views.pAttachments = &view;
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.pNext = &views;
    begin.renderPass = render_pass_;
    begin.framebuffer = framebuffer_for(frame.target);
    begin.renderArea = {{0, 0}, frame.target.extent};
    vkCmdBeginRenderPass(frame.cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    // the solid backgrounds first, each clipped to the target (a clear's rectangle must lie in it)
    for (const Backdrop& b : backdrops_) {
        const float w = float(frame.target.extent.width), h = float(frame.target.extent.height);
        const float x0 = std::clamp(std::round(b.x0), 0.0f, w), y0 = std::clamp(std::round(b.y0), 0.0f, h);
        const float x1 = std::clamp(std::round(b.x1), 0.0f, w), y1 = std::clamp(std::round(b.y1), 0.0f, h);
        if (x1 <= x0 || y1 <= y0) continue;
        VkClearAttachment clear{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
        clear.clearValue.color = {{b.rgb[0], b.rgb[1], b.rgb[2], 1.0f}};
        const VkClearRect rect{{{std::int32_t(x0), std::int32_t(y0)}, {std::uint32_t(x1 - x0), std::uint32_t(y1 - y0)}}, 0, 1};
        vkCmdClearAttachments(frame.cmd, 1, &clear, 1, &rect);
    }
    ImGui_ImplVulkan_RenderDrawData(data, frame.cmd);
    vkCmdEndRenderPass(frame.cmd);
}

}  // namespace echosim::ui

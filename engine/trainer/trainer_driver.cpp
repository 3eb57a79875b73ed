#include "trainer/trainer_driver.hpp"

#include <imgui.h>

#include "runner/frame.hpp"
#include "trainer/exam_files.hpp"

namespace echosim::trainer {

TrainerDriver::TrainerDriver(std::shared_ptr<Trainer> trainer, DriverOptions options)
    : trainer_(std::move(trainer)), options_(std::move(options))
{
    make_reports(echo::Imaging::interpolative);
}

void TrainerDriver::make_reports(echo::Imaging imaging)
{
    auto volume = options_.volume;
    auto labels = options_.labels;
    const echo::PatientCase patient = options_.patient;
    trainer_->set_report_maker(
        [volume, labels, patient, imaging](const exam::Scorer& scorer, const std::filesystem::path& out, const std::string& trainee) {
            if (!volume) throw std::logic_error("the trainer's runner holds no volume to image the stations from");
            return write_exam_report(scorer, *volume, labels.get(), patient, out, trainee, imaging);
        });
}

std::vector<runner::PassFactory> TrainerDriver::passes()
{
    return {ui_pass(), {runner::PassPlace::overlay, [this](const runner::PassSetup& setup) {
                            auto p = std::make_unique<StationSheetPass>(setup.commands, setup.format);
                            sheet_ = p.get();
                            return p;
                        }}};
}

runner::PassFactory TrainerDriver::ui_pass()
{
    return {runner::PassPlace::overlay, [this](const runner::PassSetup& setup) {
                ui::UiOptions o = options_.ui;
                if (options_.ui_scale) o.scale = options_.ui_scale();
                auto p = std::make_unique<ui::UiPass>(setup, o);
                p->set_draw([this](const session::SessionView& view, VkExtent2D extent) {
                    const echo::ImagePlane plane = image_plane();
                    act(draw_trainer(*trainer_, view, plane, extent, ui_->fonts(), ui_->scale(), screens_));
                    if (runner_) runner_->scene().camera.target_on_screen = probe_on_screen(screens_.exam_panel, extent, plane);
                    if (runner::SimulatorFrame* frame = runner_ ? runner_->frame() : nullptr; frame && trainer_->screen() == Screen::exam)
                        draw_scanner_marks(image_panel(extent, plane), frame->echo_image().scanner(), ui_->fonts(), ui_->scale());
                    update_caliper(extent);
                    if (sheet_) sheet_->set(trainer_->report(), trainer_->report_dir(), screens_.sheet_area, extent, ui_->scale());
                });
                ui_ = p.get();
                return p;
            }};
}

glm::vec2 probe_on_screen(const std::optional<ScreenState::Rect>& panel, VkExtent2D extent, const echo::ImagePlane& plane)
{
    if (!panel || extent.width == 0) return glm::vec2(0.0f);
    const float view_w = runner::scene_rect(extent, plane).width * float(extent.width);
    const float left = std::min(panel->x1, view_w);
    // the middle of the view's part right of the panel, unless too little of it is left: that
    // middle lies left / 2 px right of the view's, left / view_w of its half width
    if (view_w - left < 0.25f * view_w) return glm::vec2(0.0f);
    return glm::vec2(left / view_w, 0.0f);
}

echo::ImagePlane TrainerDriver::image_plane()
{
    if (runner::SimulatorFrame* frame = runner_ ? runner_->frame() : nullptr) return frame->echo_image().plane();
    return runner_ ? runner_->session().image_plane() : echo::ImagePlane{};
}

void TrainerDriver::update_caliper(VkExtent2D extent)
{
    caliper_hovered_ = false;
    runner::SimulatorFrame* frame = runner_ ? runner_->frame() : nullptr;
    if (!frame || !frame->echo_pass().frozen() || trainer_->screen() != Screen::exam) {
        caliper_.clear();
        return;
    }
    const ImagePanel panel = image_panel(extent, frame->echo_image().plane());
    const ImGuiIO& io = ImGui::GetIO();
    const std::optional<glm::dvec2> under = image_point_at(panel, {io.MousePos.x, io.MousePos.y});
    caliper_hovered_ = under.has_value() && !io.WantCaptureMouse;
    if (caliper_hovered_ && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) caliper_.click(*under);
    draw_caliper(caliper_, panel, ui_->fonts(), ui_->scale());
}

void TrainerDriver::feed(const ui::UiInput& input)
{
    pending_.push_back(input);
    if (ui_) ui_->feed(input);
}

void TrainerDriver::on_attach(runner::Runner& runner)
{
    runner_ = &runner;
    make_reports(runner.imaging());  // the stations imaged as the runner shows the image
}

void TrainerDriver::act(Action a)
{
    if (a == Action::quit) quit_ = true;
    if (a == Action::started && !any_case_ && trainer_->lesson().id != options_.loaded_case) case_wanted_ = trainer_->lesson().id;
}

void TrainerDriver::on_step(runner::StepContext& step)
{
    const session::SessionView& v = step.view;
    Trainer& t = *trainer_;
    // the scorer first, as `echosim exam` scores: the calls of this step answer what it saw
    if (t.screen() == Screen::exam) t.observe({v.time_s, v.probe, v.probe_force_N, v.echo, image_plane().depth_mm});
    bool active = false;
    for (const ui::UiInput& in : pending_) {
        act(t.keys(in, v.time_s, ui_ && ui_->wants_text()));
        const bool moved = in.mouse_x != last_mouse_x_ || in.mouse_y != last_mouse_y_;
        last_mouse_x_ = in.mouse_x;
        last_mouse_y_ = in.mouse_y;
        active = active || !in.empty() || moved || in.mouse_down[0] || !in.held.empty();
    }
    const bool had_input = !pending_.empty() && active;
    pending_.clear();
    act(t.tick(v.time_s, active));
    // frames: every step in a window; in a lock-step run at the steps with input, the few after
    // (ImGui answers a release the frame after it sees it), and every frame_every_steps
    if (had_input || (ui_ && ui_->queued() > 0)) input_frames_ = 2;
    const int every = options_.frame_every_steps;
    if (input_frames_ > 0 || (every > 0 && step.step % every == 0) || capture_) {
        step.want_frame(bool(capture_));
        if (input_frames_ > 0) --input_frames_;
    }
}

void TrainerDriver::on_frame(const runner::FrameContext& frame)
{
    if (capture_ && frame.pixels) {
        auto sink = std::move(capture_);
        capture_ = nullptr;
        sink(*frame.pixels);
    }
}

}  // namespace echosim::trainer

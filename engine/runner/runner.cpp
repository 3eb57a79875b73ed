#include "runner/runner.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace echosim::runner {

namespace {

void checked(const RunnerConfig& c)
{
    const std::string who = "runner configuration '" + c.name + "': ";
    if (c.session.clock == session::Clock::lock_step && !(c.lock_step_dt_s > 0 && std::isfinite(c.lock_step_dt_s)))
        throw std::invalid_argument(who + "lock_step_dt_s " + std::to_string(c.lock_step_dt_s) + " s: must be finite and > 0");
    if (c.session.clock == session::Clock::real_time && !(c.min_dt_s > 0 && c.min_dt_s <= c.max_dt_s))
        throw std::invalid_argument(who + "min_dt_s " + std::to_string(c.min_dt_s) + " s, max_dt_s " + std::to_string(c.max_dt_s) +
                                    " s: need 0 < min_dt_s <= max_dt_s");
    if (c.max_steps < 0) throw std::invalid_argument(who + "max_steps " + std::to_string(c.max_steps) + ": must be >= 0");
    if (c.output != Output::none && !c.volume) throw std::invalid_argument(who + "volume: a frame needs the echographic volume");
    if (c.output != Output::none && c.imaging == echo::Imaging::generative && !c.labels)
        throw std::invalid_argument(who + "imaging: generative imaging synthesises the image from the tissue labels, and none are given");
    if (c.output == Output::none && !c.passes.empty()) throw std::invalid_argument(who + "passes: given, but there is no frame (output none)");
    if (c.output != Output::window && c.shared_window) throw std::invalid_argument(who + "shared_window: given, but the output is not a window");
    for (const auto& o : c.observers)
        if (!o) throw std::invalid_argument(who + "observers: one is null");
}

}  // namespace

Runner::Runner(RunnerConfig config) : config_((checked(config), std::move(config)))
{
    if (config_.output != Output::none) {
        gpu::ContextOptions options = config_.gpu;
        if (config_.output == Output::window) {
            window_ = config_.shared_window ? config_.shared_window : std::make_shared<gpu::Window>(config_.window);
            options.instance_extensions = gpu::Window::required_instance_extensions();
            options.can_present = &gpu::Window::can_present;
        }
        ctx_ = std::make_unique<gpu::Context>(options);
        messages_ = ctx_->validation_counter();
    }
    scene_ = std::make_unique<DefaultScene>(config_.session);
    if (ctx_) {
        commands_ = std::make_unique<gpu::CommandPool>(*ctx_);  // this (the driver) thread's
        if (window_) {
            auto out = std::make_unique<WindowOutput>(*commands_, *window_);
            window_output_ = out.get();
            presenter_ = std::move(out);
        } else {
            presenter_ = std::make_unique<OffscreenOutput>(*commands_, config_.extent);
        }
        imaging_ = config_.imaging.value_or(default_imaging(*ctx_, config_.labels.get()));
        frame_ = std::make_unique<SimulatorFrame>(*ctx_, *commands_, presenter_->format(), *scene_, *config_.volume, config_.labels.get(),
                                                  config_.passes, imaging_);
        frame_->set_volume_pending(config_.volume_pending);
    }
    for (const auto& o : config_.observers) o->on_attach(*this);
}

Runner::~Runner() = default;

echo::Imaging default_imaging(const gpu::Context& ctx, const io::Volume* labels)
{
    const bool generative_fits = labels && ctx.device_type() != VK_PHYSICAL_DEVICE_TYPE_CPU &&
                                 labels->voxel_count() <= ctx.limits().maxTexelBufferElements;
    return generative_fits ? echo::Imaging::generative : echo::Imaging::interpolative;
}

void Runner::add_observer(std::shared_ptr<Observer> observer)
{
    if (!observer) throw std::invalid_argument("runner configuration '" + config_.name + "': add_observer: null");
    config_.observers.push_back(observer);
    observer->on_attach(*this);
}

double Runner::next_dt()
{
    if (config_.session.clock == session::Clock::lock_step) return config_.lock_step_dt_s;
    const auto now = std::chrono::steady_clock::now();
    const double since = clock_started_ ? std::chrono::duration<double>(now - last_).count() : 0.0;
    clock_started_ = true;
    last_ = now;
    return std::clamp(since, config_.min_dt_s, config_.max_dt_s);
}

bool Runner::step()
{
    if (finished_) return false;
    // every observer is asked (one may sample on the way: the soak's), then the limit
    bool stop = false;
    for (const auto& o : config_.observers) stop = o->should_stop() || stop;
    if (stop || (config_.max_steps > 0 && steps_ >= config_.max_steps)) {
        finish();
        return false;
    }
    const double dt = next_dt();
    if (config_.input && !config_.input->poll(*this, dt)) {
        finish();
        return false;
    }
    session::Session& s = scene_->session;
    // real time: the haptic loop reads the device the input just fed (or a device of its own) before
    // the view is taken, so this step's frame shows the probe where the input put it (a frame sooner)
    if (frame_ && config_.drawing == Drawing::every_step) s.await_device(kAwaitDevice);
    s.advance(dt);
    const session::SessionView& view = s.view();  // one physics step for the observers, the scene and the image
    if (config_.camera_follows_probe) scene_->camera.follow(view.probe.position, float(dt));

    StepContext step{steps_, dt, s.time(), view, s};
    for (const auto& o : config_.observers) o->on_step(step);

    if (frame_ && (config_.drawing == Drawing::every_step || step.frame_wanted)) {
        frame_->set(*scene_, view, presenter_->extent());
        io::RgbaImage* pixels = step.pixels_wanted && presenter_->can_read_back() ? &pixels_ : nullptr;
        const bool shown = presenter_->present(frame_->passes(), pixels);
        if (shown) ++frames_;
        const FrameContext frame{steps_, view, shown, shown ? pixels : nullptr};
        for (const auto& o : config_.observers) o->on_frame(frame);
    }
    ++steps_;
    return true;
}

void Runner::finish()
{
    if (finished_) return;
    finished_ = true;
    scene_->session.stop();  // first: the haptic loop ends and sends the device a zero force
    const FinishContext end{steps_, frames_, scene_->session.time()};
    for (const auto& o : config_.observers) o->on_finish(end);
}

echo::EchoImage Runner::echo_image(const echo::EchoFrame& input, bool want_labels)
{
    if (!frame_ || !presenter_->can_read_back())
        throw std::logic_error("runner configuration '" + config_.name + "': the echographic image is read back offscreen only");
    return frame_->echo_image().render(*commands_, input, want_labels);
}

}  // namespace echosim::runner

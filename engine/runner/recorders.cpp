#include "runner/recorders.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace echosim::runner {

namespace {

void make_folder(const std::filesystem::path& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot make the folder: " + ec.message());
}

}  // namespace

FrameRecorder::FrameRecorder(std::filesystem::path dir, double frames_per_s) : dir_(std::move(dir)), rate_(frames_per_s)
{
    if (!(rate_ > 0) || !std::isfinite(rate_))
        throw std::invalid_argument("frame recorder: " + std::to_string(rate_) + " frames per simulated second: must be finite and > 0");
}

std::string FrameRecorder::file_name(std::int64_t k)
{
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(k));
    return name;
}

void FrameRecorder::on_attach(Runner& runner)
{
    if (!runner.presenter() || !runner.presenter()->can_read_back())
        throw std::invalid_argument("frame recorder: the runner configuration '" + runner.config().name + "' draws no readable frame");
    make_folder(dir_);
}

void FrameRecorder::on_step(StepContext& step)
{
    pending_ = -1;
    // frame k at the first step at or after k / rate (a step longer than 1 / rate skips frames);
    // the tolerance keeps lock-step's sums of dt from missing an exact multiple
    if (step.time_s + 1e-9 < double(next_) / rate_) return;
    pending_ = next_;
    next_ = std::int64_t(std::floor(step.time_s * rate_ + 1e-9)) + 1;
    step.want_frame(true);
}

void FrameRecorder::on_frame(const FrameContext& frame)
{
    if (pending_ < 0 || !frame.pixels) return;
    const std::filesystem::path file = dir_ / file_name(pending_);
    io::write_png(file, *frame.pixels);
    written_.push_back(file);
    pending_ = -1;
}

io::RgbaImage to_rgba(const echo::EchoImage& image)
{
    io::RgbaImage out;
    out.width = image.columns;
    out.height = image.rows;
    out.pixels.resize(image.rgba.size() * 4);
    std::memcpy(out.pixels.data(), image.rgba.data(), out.pixels.size());  // little-endian R, G, B, A
    return out;
}

ImageRecorder::ImageRecorder(std::filesystem::path dir, Pick pick, bool want_labels)
    : dir_(std::move(dir)), pick_(std::move(pick)), want_labels_(want_labels)
{
    if (!pick_) throw std::invalid_argument("image recorder: no rule picks its steps");
}

void ImageRecorder::on_attach(Runner& runner)
{
    if (!runner.presenter() || !runner.presenter()->can_read_back())
        throw std::invalid_argument("image recorder: the runner configuration '" + runner.config().name + "' has no offscreen frame");
    runner_ = &runner;
    make_folder(dir_);
}

void ImageRecorder::on_step(StepContext& step)
{
    const std::string name = pick_(step);
    if (name.empty()) return;
    Recorded r{step.step, step.time_s, dir_ / (name + ".png"), runner_->echo_image(*step.view.echo, want_labels_)};
    io::write_png(r.file, to_rgba(r.image));
    recorded_.push_back(std::move(r));
}

}  // namespace echosim::runner

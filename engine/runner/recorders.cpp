#include "runner/recorders.hpp"

#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace echosim::runner {

namespace {

void make_folder(const std::filesystem::path& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot make the folder: " + ec.message());
}

}  // namespace

// The recorder's writer: one thread taking (file, frame) pairs off a queue of at most kQueued and
// writing them in order. Hand-offs under `mutex`: the driver pushes (waiting while the queue is
// full) and takes the first error; the thread pops and sets it. The frames' buffers go round: a
// written frame's buffer is reused for a later one (no allocation once two are made).
struct FrameRecorder::Writer {
    static constexpr std::size_t kQueued = 2;
    struct Job {
        std::filesystem::path file;
        io::RgbaImage image;
    };
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<Job> queue;
    std::vector<io::RgbaImage> spare;
    std::exception_ptr error;
    bool closing = false;
    std::thread thread{[this] { run(); }};

    ~Writer()
    {
        {
            const std::lock_guard lock(mutex);
            closing = true;
        }
        changed.notify_all();
        thread.join();
    }
    void run()
    {
        std::unique_lock lock(mutex);
        for (;;) {
            changed.wait(lock, [&] { return closing || !queue.empty(); });
            if (queue.empty()) return;  // closing, and all written
            Job job = std::move(queue.front());
            lock.unlock();
            std::exception_ptr failed;
            try {
                if (!error) io::write_png(job.file, job.image);  // after a failure the rest are dropped
            } catch (...) {
                failed = std::current_exception();
            }
            lock.lock();
            queue.pop_front();
            if (failed && !error) error = failed;
            spare.push_back(std::move(job.image));
            changed.notify_all();
        }
    }
    // Queues `image` for `file` (copied into a spare buffer); rethrows a failure of an earlier one.
    void push(const std::filesystem::path& file, const io::RgbaImage& image)
    {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return queue.size() < kQueued || error; });
        rethrow_locked();
        io::RgbaImage copy;
        if (!spare.empty()) {
            copy = std::move(spare.back());
            spare.pop_back();
        }
        copy.width = image.width;
        copy.height = image.height;
        copy.pixels.assign(image.pixels.begin(), image.pixels.end());
        queue.push_back({file, std::move(copy)});
        changed.notify_all();
    }
    // Waits until everything queued is written; rethrows the first failure.
    void drain()
    {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return queue.empty(); });
        rethrow_locked();
    }
    void rethrow_locked()
    {
        if (error) std::rethrow_exception(std::exchange(error, nullptr));
    }
};

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

FrameRecorder::~FrameRecorder() = default;  // the writer's thread finishes what is queued

void FrameRecorder::on_frame(const FrameContext& frame)
{
    if (pending_ < 0 || !frame.pixels) return;
    const std::filesystem::path file = dir_ / file_name(pending_);
    if (!writer_) writer_ = std::make_unique<Writer>();
    writer_->push(file, *frame.pixels);
    written_.push_back(file);
    pending_ = -1;
}

void FrameRecorder::on_finish(const FinishContext&)
{
    if (writer_) writer_->drain();
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

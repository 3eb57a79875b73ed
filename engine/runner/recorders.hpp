// Observers that write what a run shows (runner/runner.hpp):
//   - FrameRecorder: the frame (the leg and the image panel, as the offscreen presenter drew it) as
//     PNG files at a rate per simulated second, frame_000000.png on; lock-step runs write the same
//     bytes every time. The PNGs are encoded and written on a thread of the recorder's own (the
//     driver hands it a copy of the frame through a queue of at most two, and waits when it is
//     full), so the run goes on while a frame is compressed; a file that cannot be written ends
//     the run at the next frame or at its end;
//   - ImageRecorder: the echographic image itself, at full resolution, as a grey PNG at the steps
//     the caller picks (an exam's deepest press at each station), with the image and its stages'
//     outputs kept for the caller (EchoImage: the deformed labels too, when asked for).
// Both need an offscreen runner (the frames are read back); files that cannot be written throw
// std::runtime_error naming the file, which ends the run where it is.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "echo/echo_frame.hpp"
#include "runner/runner.hpp"

namespace echosim::runner {

class FrameRecorder final : public Observer {
public:
    // `frames_per_s` [1/s of simulated time] > 0 and finite, else std::invalid_argument. The folder
    // is made when the recorder joins a runner.
    FrameRecorder(std::filesystem::path dir, double frames_per_s);

    ~FrameRecorder() override;
    FrameRecorder(const FrameRecorder&) = delete;
    FrameRecorder& operator=(const FrameRecorder&) = delete;

    void on_attach(Runner& runner) override;
    void on_step(StepContext& step) override;
    void on_frame(const FrameContext& frame) override;
    void on_finish(const FinishContext& finish) override;  // waits for the last file

    // the files written (all of them once the run has finished)
    const std::vector<std::filesystem::path>& written() const { return written_; }
    // frame k is the first step at or after k / frames_per_s of simulated time
    static std::string file_name(std::int64_t k);

private:
    std::filesystem::path dir_;
    double rate_;
    std::int64_t next_ = 0;      // the next frame's number
    std::int64_t pending_ = -1;  // the frame this step asked for
    std::vector<std::filesystem::path> written_;
    struct Writer;                    // the thread and its queue (recorders.cpp)
    std::unique_ptr<Writer> writer_;
};

class ImageRecorder final : public Observer {
public:
    // Says, each step, under which file name (in `dir`, ".png" added) to record the step's
    // echographic image; "" records none.
    using Pick = std::function<std::string(const StepContext& step)>;
    ImageRecorder(std::filesystem::path dir, Pick pick, bool want_labels = false);

    void on_attach(Runner& runner) override;
    void on_step(StepContext& step) override;

    struct Recorded {
        std::int64_t step = 0;
        double time_s = 0;
        std::filesystem::path file;
        echo::EchoImage image;
    };
    const std::vector<Recorded>& recorded() const { return recorded_; }

private:
    std::filesystem::path dir_;
    Pick pick_;
    bool want_labels_;
    Runner* runner_ = nullptr;
    std::vector<Recorded> recorded_;
};

// The echographic image as an RGBA PNG image (its display bytes, grey).
io::RgbaImage to_rgba(const echo::EchoImage& image);

}  // namespace echosim::runner

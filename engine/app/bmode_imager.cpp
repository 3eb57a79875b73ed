#include "app/bmode_imager.hpp"

#include <cstdio>
#include <exception>

#include "gpu/command_pool.hpp"
#include "image/bmode_gpu.hpp"

namespace echosim::app {
namespace {

// The GPU imager with the context and pool it runs on; they go after it (members in reverse).
class OwnedGpuImager : public echo::SweepImager {
public:
    OwnedGpuImager(const io::Volume& labels, const echo::ScanSpec& spec, const gpu::ContextOptions& options)
        : ctx_(std::make_unique<gpu::Context>(options)), pool_(std::make_unique<gpu::CommandPool>(*ctx_)),
          bmode_(std::make_unique<image::BModeGpu>(*pool_, labels, spec))
    {
    }
    std::size_t batch_frames() const override { return bmode_->batch_frames(); }
    void image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels) override { bmode_->image(poses, pixels, labels); }
    std::string backend() const override { return bmode_->backend(); }

private:
    std::unique_ptr<gpu::Context> ctx_;
    std::unique_ptr<gpu::CommandPool> pool_;
    std::unique_ptr<image::BModeGpu> bmode_;
};

}  // namespace

std::unique_ptr<echo::SweepImager> make_bmode_imager(std::shared_ptr<const io::Volume> labels, const echo::ScanSpec& spec,
                                                     const gpu::ContextOptions& options, const std::string& command)
{
    try {
        return std::make_unique<OwnedGpuImager>(*labels, spec, options);
    } catch (const std::invalid_argument&) {
        throw;  // the spec or the volume: the CPU twin would refuse them too
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: no usable Vulkan device (%s): synthesising on the CPU\n", command.c_str(), e.what());
    }
    return std::make_unique<echo::CpuSweepImager>(std::move(labels), spec);
}

}  // namespace echosim::app

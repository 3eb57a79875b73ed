#include "haptics/cpu_wake_latency.hpp"

#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

namespace echosim::haptics {

CpuWakeLatency::CpuWakeLatency(std::int32_t max_us, const std::string& file)
{
    if (max_us < 0) {
        refusal_ = file + ": a wake latency of " + std::to_string(max_us) + " us is not a bound";
        return;
    }
    fd_ = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) {
        const int error = errno;
        refusal_ = file + ": " + std::strerror(error);
        if (error == EACCES || error == EPERM) refusal_ += " (root may write it, or a udev rule let a group write it)";
        return;
    }
    // the value is a binary 32-bit integer (the kernel also takes hex text; binary is exact)
    ssize_t written = ::write(fd_, &max_us, sizeof max_us);
    if (written != ssize_t(sizeof max_us)) {
        refusal_ = file + ": " + (written < 0 ? std::string(std::strerror(errno)) : "short write of the bound");
        release();
    }
}

CpuWakeLatency::~CpuWakeLatency() { release(); }

CpuWakeLatency::CpuWakeLatency(CpuWakeLatency&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), refusal_(std::move(other.refusal_))
{
}

CpuWakeLatency& CpuWakeLatency::operator=(CpuWakeLatency&& other) noexcept
{
    if (this != &other) {
        release();
        fd_ = std::exchange(other.fd_, -1);
        refusal_ = std::move(other.refusal_);
    }
    return *this;
}

void CpuWakeLatency::release()
{
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

}  // namespace echosim::haptics

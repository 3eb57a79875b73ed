// A request that the CPUs wake from idle within a bound, held while the haptic loop runs (Linux PM
// QoS: the request lives as long as /dev/cpu_dma_latency stays open with the bound written to it).
//
// Why the loop needs it: between ticks its thread sleeps, and a CPU with nothing else to run goes
// idle. Waking a deep idle state takes tens to hundreds of microseconds on a PC; a virtual CPU that
// halts is woken by its hypervisor, on a shared host after a millisecond or more. The loop's clock
// then fires late however high its priority. Measured on the CI-class 2-core VM (bench/RESULTS.md,
// "Soak"): the 1 kHz loop's period error p99 0.93 ms and 522 missed deadlines in a minute without
// the request, 0.03 ms and 5 with it. The cost is power: the idle CPUs poll instead of sleeping, for
// as long as the loop runs.
#pragma once

#include <cstdint>
#include <string>

namespace echosim::haptics {

class CpuWakeLatency {
public:
    static constexpr const char* kDevice = "/dev/cpu_dma_latency";

    CpuWakeLatency() = default;  // holds nothing
    // Asks, through `file`, that the CPUs wake within `max_us` microseconds (0: never idle deeper
    // than polling). Never throws: a refusal (no such file, not permitted) is held as a message.
    explicit CpuWakeLatency(std::int32_t max_us, const std::string& file = kDevice);
    ~CpuWakeLatency();
    CpuWakeLatency(CpuWakeLatency&& other) noexcept;
    CpuWakeLatency& operator=(CpuWakeLatency&& other) noexcept;
    CpuWakeLatency(const CpuWakeLatency&) = delete;
    CpuWakeLatency& operator=(const CpuWakeLatency&) = delete;

    bool held() const { return fd_ >= 0; }
    // why the request is not held, naming the file ("" when held, or when nothing was asked)
    const std::string& refusal() const { return refusal_; }
    void release();  // the kernel drops the request when the file closes

private:
    int fd_ = -1;
    std::string refusal_;
};

}  // namespace echosim::haptics

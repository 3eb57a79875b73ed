// The haptic loop (DESIGN.md §1 and §2, paper §5.2): every millisecond it reads the device, places
// the probe, renders the force from the physics' latest local contact model, sends it to the device,
// and hands the probe's pose and velocity to the physics, which works out the tissue's side of the
// same contact (the penalty on the skin nodes: the reaction) at its own, slower rate.
//
// Hand-offs, all lock-free triple buffers (latest wins), so the loop never waits for anyone:
//   in:  the LocalContactModel the physics publishes after each step (the loop is its one reader)
//   out: the probe command to the physics (the loop is its one producer while it runs)
//   out: a HapticSample to the session's driver thread (pose, force felt, device state)
// The device's own hand-offs are the driver's (device/device.hpp). Nothing in a tick allocates,
// locks or throws.
//
// Two clocks, as the physics has: start() runs the loop on a thread of its own, sleeping to absolute
// deadlines (clock_nanosleep) and spinning only the last few tens of microseconds; tick(t) runs one
// tick in the caller's thread at simulated time t, so a headless exam or a test is reproducible.
//
// A real-time start also keeps the loop from waiting on memory (issue 34): the process's memory
// locked (memory_lock.hpp), the thread's stack and the loop's own buffers faulted in before the first
// tick, the thread fixed on one CPU; its page faults after that are counted (PeriodStats::page_faults).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "core/triple_buffer.hpp"
#include "device/device.hpp"
#include "haptics/cpu_wake_latency.hpp"
#include "haptics/force_law.hpp"
#include "haptics/memory_lock.hpp"
#include "haptics/period_stats.hpp"
#include "haptics/probe_mapping.hpp"
#include "physics/physics_runner.hpp"

namespace echosim::haptics {

struct HapticOptions {
    double rate_hz = 1000.0;
    double spin_us = 60.0;          // spin this long before each deadline instead of sleeping
    bool local_model = true;        // false: hold the last physics force (the paper's comparison)
    bool realtime_priority = true;  // ask for SCHED_FIFO (needs CAP_SYS_NICE or an rtprio limit)
    bool keep_cpus_awake = true;    // with realtime_priority: hold a CpuWakeLatency request of 0 us while running
    bool lock_memory = true;        // with realtime_priority: mlockall while running (memory_lock.hpp)
    bool pin_cpu = true;            // with SCHED_FIFO granted: run on the last CPU the process may use
    double velocity_cutoff_hz = 20; // the probe's velocity, from its poses, low-passed
};

struct HapticSample {
    std::int64_t tick = 0;
    double time_s = 0;                // the loop's clock
    ProbeFace face;                   // where the device put the probe
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // [mm/s], low-passed
    HapticForce force;                // rendered (and sent to the device)
    double model_force_N = 0;         // the latest local model at this pose, before the refresh blend
    double physics_force_N = 0;       // the last physics step's own force along the axis
    std::int64_t physics_step = 0;    // the step the local model came from
    device::DeviceSample device;      // the device's sample this tick
};

class HapticLoop {
public:
    // `physics` and `mapping` must outlive the loop; the loop becomes the physics' one commander.
    HapticLoop(physics::PhysicsRunner& physics, std::shared_ptr<device::Device> device, const ProbeMapping& mapping,
               const HapticOptions& options = {});
    ~HapticLoop();
    HapticLoop(const HapticLoop&) = delete;
    HapticLoop& operator=(const HapticLoop&) = delete;

    // lock-step: one tick at time t [s] (not while the thread runs)
    void tick(double t_s);

    // real time: the loop's thread; start() returns once it runs, its priority settled
    void start();
    // Ends the thread (if it runs) and sends the device a zero force; also on destruction.
    void stop();
    bool running() const { return running_.load(); }
    // "" when it runs real time (SCHED_FIFO, the CPUs kept from idling deeper than polling:
    // cpu_wake_latency.hpp, the memory locked, pinned where there is a CPU to choose), else what it
    // lacks and why (said once, by whoever starts it)
    const std::string& priority_note() const { return priority_note_; }
    bool cpus_awake() const { return wake_latency_.held(); }
    bool memory_locked() const { return memory_lock_.held(); }
    int cpu() const { return cpu_; }  // the CPU the running loop is pinned to, -1 when none

    // the session's driver thread (one reader): the latest tick
    const HapticSample& latest() { return out_.read(); }
    // the timing so far (a copy; the loop's thread keeps adding)
    PeriodStats stats();  // the driver thread (one reader)
    std::int64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }
    // From the next tick on, PeriodStats::window_max_late_ms covers only what follows: the loop's
    // latest tick over the same spell as a measurement beside it (cyclictest), not its set-up's.
    void restart_window() { window_.fetch_add(1, std::memory_order_relaxed); }
    const device::Device& device() const { return *device_; }
    double period_s() const { return 1.0 / options_.rate_hz; }

private:
    void run();

    physics::PhysicsRunner& physics_;
    std::shared_ptr<device::Device> device_;
    const ProbeMapping& mapping_;
    HapticOptions options_;
    ForceLimits limits_;
    // the ticking thread's own
    HapticSample now_;
    bool have_last_ = false;
    double last_t_ = 0;
    Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
    physics::LocalContactModel model_;  // the model being rendered (a copy: the next read may replace it)
    bool have_model_ = false;
    RefreshBlend blend_;
    PeriodStats stats_;
    // the running loop's clock readings in the tick under way (CLOCK_MONOTONIC [ns]): its start, after
    // the device's read, the force, the device's write, the hand-offs (PeriodStats::worst); lock-step
    // ticks take none
    bool stamp_parts_ = false;
    std::int64_t stamps_[5] = {};
    // hand-offs
    TripleBuffer<HapticSample> out_;
    TripleBuffer<PeriodStats> stats_out_;  // published every 100 ticks, for stats() while running
    std::atomic<std::int64_t> ticks_{0};
    std::atomic<std::uint32_t> window_{0};  // restart_window()'s count
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::atomic<int> started_{0};  // 0 starting, 1 running (the thread settled its priority)
    std::string priority_note_;
    int priority_errno_ = 0;
    CpuWakeLatency wake_latency_;  // held from start() to stop()
    MemoryLock memory_lock_;       // held from start() to stop()
    int cpu_ = -1;
    std::string pin_refusal_;      // set by the thread before it says it runs
};

}  // namespace echosim::haptics

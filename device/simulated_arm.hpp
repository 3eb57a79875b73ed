// A simulated force-feedback arm, standing in for a Touch or an omega in tests, benches and demos:
// its handle (device/arm_dynamics.hpp: a mass with friction and end stops) is held by a simulated
// hand through a virtual coupling and pushed by the force the haptic loop renders, so the whole
// force path runs here without hardware: the loop's force -> the arm's dynamics -> the handle's
// pose back -> the probe's pose -> the tissue's force.
//
// Threads. As a real arm's SDK does, it runs a servo of its own (Servo::thread): a 1 kHz thread,
// sleeping to absolute deadlines, that takes the latest force the loop sent (a triple buffer),
// steps the handle over the time since its last tick, and publishes the handle's pose (another
// triple buffer). read() and write_force() never wait for it. Servo::lock_step has no thread:
// read(t) steps the handle up to the loop's time t itself (in steps of at most one servo period),
// so a lock-step test or headless run gives the same figures every time.
//
// Forces are cut to max_force_N (keeping their direction; a NaN is no force), and a force the loop
// has not renewed for kForceHoldS is dropped (device.hpp), in real time as on a real arm; the
// destructor stops the servo with no force applied.
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>

#include "core/triple_buffer.hpp"
#include "device/arm_dynamics.hpp"
#include "device/device.hpp"

namespace echosim::device {

// What the simulated hand does: where it wants the handle at time t [s] (the servo's clock).
struct HandScript {
    enum class Kind {
        hold,         // the hand holds `hold_mm`
        press_cycle,  // straight down along the device's y and back up, a cosine over `period_s`
    };
    Kind kind = Kind::press_cycle;
    Eigen::Vector3d hold_mm = Eigen::Vector3d::Zero();
    // With device/README.md's mapping (the workspace origin 20 mm above the skin, scale 1), the
    // hand goes from 20 mm above the skin to 25 mm into it and back every 4 s; the handle lags the
    // hand by the tissue's push over the coupling's stiffness.
    double top_y_mm = 0, bottom_y_mm = -45, period_s = 4;
    Eigen::Vector3d at(double t_s) const;
};

struct SimulatedArmOptions {
    enum class Servo { thread, lock_step };
    Servo servo = Servo::thread;
    double rate_hz = 1000;
    ArmParameters arm;
    HandScript hand;
    // What it renders, in the range of a desktop arm of the Touch's reach with a stronger motor (an
    // omega.3 renders 12 N and 14.5 N/mm): enough to feel the thigh push back. The stiffness and the
    // damping stay where this arm's mass and friction keep a 1 kHz contact stable (its own damping
    // above half the stiffness times the period: Colgate's passivity bound).
    double max_force_N = 6.0;
    double max_stiffness_N_per_mm = 2.0;
    double max_damping_N_s_per_mm = 0.004;
};

class SimulatedArm : public Device {
public:
    // Throws std::invalid_argument naming the field when the options make no arm.
    explicit SimulatedArm(const SimulatedArmOptions& options = {});
    ~SimulatedArm() override;
    SimulatedArm(const SimulatedArm&) = delete;
    SimulatedArm& operator=(const SimulatedArm&) = delete;

    const Capabilities& capabilities() const override { return caps_; }
    bool read(double t_s, DeviceSample& out) noexcept override;
    void write_force(const Eigen::Vector3d& force_N) noexcept override;
    void events(std::vector<DeviceEvent>& out) override;

    // Any thread: the force the servo applied at its latest tick [N] (after the cut and the hold
    // limit; its components may come from consecutive ticks), and how many ticks it ran.
    Eigen::Vector3d applied_force() const;
    std::int64_t servo_ticks() const { return ticks_.load(std::memory_order_relaxed); }

private:
    struct Command {
        Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
        std::int64_t stamp_ns = 0;  // steady clock; 0: never sent
    };
    Eigen::Vector3d cut(const Eigen::Vector3d& f) const;
    void advance(double t_s, const Eigen::Vector3d& force_N);  // the servo's own state, to time t_s
    DeviceSample sample() const;
    void run() noexcept;

    SimulatedArmOptions options_;
    Capabilities caps_;
    // the servo's own (the servo thread's, or in lock-step the haptic thread's)
    ArmState state_;
    double servo_t_ = 0;
    bool started_ = false;
    std::uint64_t sequence_ = 0;
    Eigen::Vector3d lock_step_force_ = Eigen::Vector3d::Zero();
    // hand-offs
    TripleBuffer<DeviceSample> pose_;  // servo thread -> haptic thread
    TripleBuffer<Command> command_;    // haptic thread -> servo thread
    std::atomic<double> applied_[3] = {0.0, 0.0, 0.0};
    std::atomic<std::int64_t> ticks_{0};
    std::atomic<bool> stop_{false};
    bool announced_ = false;  // the driver thread's
    std::thread servo_;       // last: it starts once everything above is made
};

}  // namespace echosim::device

#include "device/simulated_arm.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <stdexcept>
#include <string>

namespace echosim::device {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
// the longest step the servo takes at once [s]: a thread held up (a loaded machine) moves the handle
// as if the time had passed at this rate, not in one leap
constexpr double kMaxStepS = 0.005;

std::int64_t now_ns()
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return std::int64_t(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

DeviceSample resting(const Eigen::Vector3d& position)
{
    DeviceSample s;
    s.connected = true;
    s.control = Control::workspace;
    s.position = position;
    return s;
}

}  // namespace

Eigen::Vector3d HandScript::at(double t_s) const
{
    if (kind == Kind::hold) return hold_mm;
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * t_s / period_s);
    return {hold_mm.x(), top_y_mm + w * (bottom_y_mm - top_y_mm), hold_mm.z()};
}

SimulatedArm::SimulatedArm(const SimulatedArmOptions& options)
    : options_(options), state_{options.hand.at(0.0), Eigen::Vector3d::Zero()}, pose_(resting(options.hand.at(0.0)))
{
    if (const char* field = invalid_field(options_.arm); *field != '\0')
        throw std::invalid_argument(std::string("simulated arm: ArmParameters::") + field + " out of range");
    if (!(options_.rate_hz >= 100 && options_.rate_hz <= 20000))
        throw std::invalid_argument("simulated arm: servo rate " + std::to_string(options_.rate_hz) + " Hz outside 100..20000");
    if (!(options_.hand.period_s > 0 && std::isfinite(options_.hand.period_s) && options_.hand.hold_mm.allFinite() &&
          std::isfinite(options_.hand.top_y_mm) && std::isfinite(options_.hand.bottom_y_mm)))
        throw std::invalid_argument("simulated arm: the hand's script is not finite (period_s > 0)");
    if (!(options_.max_force_N > 0 && options_.max_stiffness_N_per_mm > 0 && options_.max_damping_N_s_per_mm >= 0 &&
          std::isfinite(options_.max_force_N + options_.max_stiffness_N_per_mm + options_.max_damping_N_s_per_mm)))
        throw std::invalid_argument("simulated arm: max_force_N and max_stiffness_N_per_mm must be positive");

    caps_.name = "simulated arm";
    caps_.driver = "simulated";
    const bool threaded = options_.servo == SimulatedArmOptions::Servo::thread;
    char where[96];
    std::snprintf(where, sizeof where, "%s at %.0f Hz", threaded ? "its own servo thread" : "lock-step with the loop", options_.rate_hz);
    caps_.address = where;
    caps_.control = Control::workspace;
    caps_.degrees_of_freedom = 3;  // the handle moves; it does not turn
    caps_.buttons = 0;
    caps_.report_rate_hz = options_.rate_hz;
    caps_.workspace_mm = options_.arm.workspace_mm;
    caps_.max_force_N = options_.max_force_N;
    caps_.max_stiffness_N_per_mm = options_.max_stiffness_N_per_mm;
    caps_.max_damping_N_s_per_mm = options_.max_damping_N_s_per_mm;

    if (threaded) servo_ = std::thread([this] { run(); });
}

SimulatedArm::~SimulatedArm()
{
    stop_.store(true, std::memory_order_release);
    if (servo_.joinable()) servo_.join();
}

Eigen::Vector3d SimulatedArm::cut(const Eigen::Vector3d& f) const
{
    if (!f.allFinite()) return Eigen::Vector3d::Zero();
    const double n = f.norm();
    return n > options_.max_force_N ? Eigen::Vector3d(f * (options_.max_force_N / n)) : f;
}

void SimulatedArm::advance(double t_s, const Eigen::Vector3d& force_N)
{
    const double period = 1.0 / options_.rate_hz;
    while (servo_t_ < t_s) {
        const double dt = std::min(period, t_s - servo_t_);
        servo_t_ += dt;
        step(options_.arm, state_, options_.hand.at(servo_t_), force_N, dt);
    }
    for (int i = 0; i < 3; ++i) applied_[i].store(force_N[i], std::memory_order_relaxed);
    ticks_.fetch_add(1, std::memory_order_relaxed);
}

DeviceSample SimulatedArm::sample() const
{
    DeviceSample s = resting(state_.position_mm);
    s.sequence = sequence_;
    return s;
}

bool SimulatedArm::read(double t_s, DeviceSample& out) noexcept
{
    if (options_.servo == SimulatedArmOptions::Servo::lock_step) {
        // the loop's clock is the servo's: the handle moves to time t under the force sent last tick
        if (!started_) {
            started_ = true;
            servo_t_ = t_s;
        }
        if (t_s > servo_t_) {
            advance(t_s, lock_step_force_);
            ++sequence_;
        }
        out = sample();
        return true;
    }
    out = pose_.read();
    return out.connected;
}

void SimulatedArm::write_force(const Eigen::Vector3d& force_N) noexcept
{
    if (options_.servo == SimulatedArmOptions::Servo::lock_step) {
        lock_step_force_ = cut(force_N);
        return;
    }
    Command& c = command_.write_slot();
    c.force_N = force_N;
    c.stamp_ns = now_ns();
    command_.publish();
}

Eigen::Vector3d SimulatedArm::applied_force() const
{
    return {applied_[0].load(std::memory_order_relaxed), applied_[1].load(std::memory_order_relaxed), applied_[2].load(std::memory_order_relaxed)};
}

void SimulatedArm::events(std::vector<DeviceEvent>& out)
{
    if (announced_) return;
    announced_ = true;
    const HandScript& h = options_.hand;
    char what[256];
    if (h.kind == HandScript::Kind::press_cycle)
        std::snprintf(what, sizeof what,
                      "%s: a simulated hand moves the handle from y %.0f mm to %.0f mm and back every %.1f s through a %.2f N/mm coupling; "
                      "forces up to %.1f N",
                      caps_.address.c_str(), h.top_y_mm, h.bottom_y_mm, h.period_s, options_.arm.coupling_N_per_mm, caps_.max_force_N);
    else
        std::snprintf(what, sizeof what, "%s: a simulated hand holds the handle at (%.0f, %.0f, %.0f) mm through a %.2f N/mm coupling",
                      caps_.address.c_str(), h.hold_mm.x(), h.hold_mm.y(), h.hold_mm.z(), options_.arm.coupling_N_per_mm);
    out.push_back({DeviceEvent::Kind::connected, caps_.name, what});
}

void SimulatedArm::run() noexcept
{
    const std::int64_t period = std::int64_t(std::llround(1e9 / options_.rate_hz));
    const std::int64_t origin = now_ns();
    std::int64_t due = origin, last = origin;
    while (!stop_.load(std::memory_order_acquire)) {
        due += period;
        const timespec ts{time_t(due / kNsPerS), long(due % kNsPerS)};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
        }
        const std::int64_t now = now_ns();
        if (now > due + period) due = now;  // late by more than a tick: no burst to catch up
        // the force the loop sent, if it is still being renewed
        const Command& c = command_.read();
        const bool fresh = c.stamp_ns != 0 && double(now - c.stamp_ns) * 1e-9 <= kForceHoldS;
        const Eigen::Vector3d f = fresh ? cut(c.force_N) : Eigen::Vector3d::Zero();
        const double dt = std::min(double(now - last) * 1e-9, kMaxStepS);
        last = now;
        advance(servo_t_ + dt, f);
        ++sequence_;
        pose_.write_slot() = sample();
        pose_.publish();
    }
    for (std::atomic<double>& a : applied_) a.store(0.0, std::memory_order_relaxed);
}

}  // namespace echosim::device

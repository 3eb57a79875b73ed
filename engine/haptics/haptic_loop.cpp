#include "haptics/haptic_loop.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <numbers>
#include <ctime>
#include <stdexcept>

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>

#include "haptics/realtime_thread.hpp"

namespace echosim::haptics {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

std::int64_t now_ns()
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return std::int64_t(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t t)
{
    const timespec ts{time_t(t / kNsPerS), long(t % kNsPerS)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
}

inline void cpu_relax()
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

}  // namespace

HapticLoop::HapticLoop(physics::PhysicsRunner& physics, std::shared_ptr<device::Device> device, const ProbeMapping& mapping,
                       const HapticOptions& options)
    : physics_(physics), device_(std::move(device)), mapping_(mapping), options_(options)
{
    if (!device_) throw std::invalid_argument("HapticLoop: no device (use device::NullDevice for none)");
    if (!(options_.rate_hz >= 10.0 && options_.rate_hz <= 20000.0))
        throw std::invalid_argument("HapticLoop: rate " + std::to_string(options_.rate_hz) + " Hz outside 10..20000");
    limits_ = ForceLimits::of(device_->capabilities());
}

HapticLoop::~HapticLoop() { stop(); }

void HapticLoop::tick(double t_s)
{
    if (stamp_parts_) stamps_[0] = now_ns();
    HapticSample& s = now_;
    device_->read(t_s, s.device);
    if (stamp_parts_) stamps_[1] = now_ns();
    s.face = mapping_.face(s.device);
    // velocity from the poses, low-passed: a device that reports slower than the loop moves in steps
    const double dt = have_last_ ? t_s - last_t_ : 0.0;
    if (dt > 0.0) {
        const Eigen::Vector3d raw = (s.face.position - last_position_) / dt;
        const double a = 1.0 - std::exp(-2.0 * std::numbers::pi * options_.velocity_cutoff_hz * dt);
        s.velocity += a * (raw - s.velocity);
    }
    have_last_ = true;
    last_t_ = t_s;
    last_position_ = s.face.position;

    const physics::LocalContactModel& model = physics_.latest_contact();
    if (options_.local_model) {
        s.force = local_model_force(model, s.face.position, s.velocity, limits_);
        s.model_force_N = s.force.along_N;
        if (!have_model_ || model.step != model_.step) {
            if (have_model_) {
                const double before = local_model_force(model_, s.face.position, s.velocity, limits_).along_N;
                blend_.refresh(t_s, before, s.force.along_N, model.time - model_.time);
            }
            model_ = model;
            have_model_ = true;
        }
        const double blended = std::min(blend_.apply(s.force.along_N, t_s), limits_.max_force_N > 0 ? limits_.max_force_N : 1e300);
        s.force.along_N = blended;
        s.force.world_N = -blended * model_.axis;
    } else {
        s.force = held_physics_force(model, limits_);
        s.model_force_N = s.force.along_N;
    }
    s.physics_force_N = model.in_contact ? model.force : 0.0;
    s.physics_step = model.step;
    if (stamp_parts_) stamps_[2] = now_ns();
    device_->write_force(mapping_.to_device(s.force.world_N, s.device.control));
    if (stamp_parts_) stamps_[3] = now_ns();

    physics::ProbeCommand c;
    c.active = true;
    c.position = s.face.position;
    c.orientation = s.face.orientation;
    c.velocity = s.velocity;
    physics_.command(c);  // a NaN from a device is refused there, counted, and the probe holds

    s.tick = ticks_.fetch_add(1, std::memory_order_relaxed) + 1;
    s.time_s = t_s;
    out_.write_slot() = s;
    out_.publish();
    if (stamp_parts_) stamps_[4] = now_ns();
}

void HapticLoop::start()
{
    if (running_.exchange(true)) return;
    if (options_.realtime_priority && options_.keep_cpus_awake) wake_latency_ = CpuWakeLatency(0);
    // before the thread is made: MCL_FUTURE locks its stack as it is mapped
    if (options_.realtime_priority && options_.lock_memory) memory_lock_ = MemoryLock::lock_all();
    started_ = 0;
    thread_ = std::thread([this] { run(); });
    while (started_.load(std::memory_order_acquire) == 0) std::this_thread::yield();
    priority_note_.clear();
    if (!options_.realtime_priority) {
        priority_note_ = "haptic loop: real-time priority not asked for; running best effort";
        return;
    }
    if (priority_errno_ != 0)
        priority_note_ = std::string("haptic loop: real-time priority (SCHED_FIFO) refused: ") + std::strerror(priority_errno_) +
                         "; running best effort (grant it with an rtprio limit in /etc/security/limits.d, or CAP_SYS_NICE)";
    if (!wake_latency_.refusal().empty())
        priority_note_ += std::string(priority_note_.empty() ? "haptic loop: " : "; ") + "the CPUs may idle between ticks and wake late (" +
                          wake_latency_.refusal() + ")";
    // a page fault may then stall a tick behind another thread's memory work
    if (!memory_lock_.refusal().empty()) priority_note_ += std::string(priority_note_.empty() ? "haptic loop: " : "; ") + memory_lock_.refusal();
    if (!pin_refusal_.empty()) priority_note_ += std::string(priority_note_.empty() ? "haptic loop: " : "; ") + pin_refusal_;
}

void HapticLoop::stop()
{
    if (running_.exchange(false)) {
        if (thread_.joinable()) thread_.join();
        wake_latency_.release();
        memory_lock_.release();
    }
    // the hand is let go first, whatever stops the session (its end, a signal, an error): a device
    // that renders force is sent none from here on (the loop's thread, which sent the last, has
    // ended; in lock-step the caller is the ticking thread)
    device_->write_force(Eigen::Vector3d::Zero());
}

PeriodStats HapticLoop::stats()
{
    if (running_) return stats_out_.read();
    return stats_;
}

void HapticLoop::run()
{
    // timer slack: the kernel may otherwise wake us up to 50 us late, on purpose
    prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
    priority_errno_ = 0;
    if (options_.realtime_priority) {
        sched_param p{};
        p.sched_priority = sched_get_priority_max(SCHED_FIFO) - 10;
        priority_errno_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
    }
    // pinned only with SCHED_FIFO: a best-effort thread fixed to one CPU could not flee a busy one
    cpu_ = -1;
    pin_refusal_.clear();
    if (options_.realtime_priority && options_.pin_cpu && priority_errno_ == 0) cpu_ = pin_to_last_cpu(pin_refusal_);
    // Nothing left to fault in after this: the stack a tick uses and the state only this thread
    // touches (written once at construction, by another thread: read here; the hand-off slots it
    // fills next: written here). Faults from here on are counted.
    prefault_stack();
    prefault_read(&now_, sizeof now_);
    prefault_read(&model_, sizeof model_);
    prefault_read(&stats_, sizeof stats_);
    stats_out_.write_slot() = stats_;
    out_.write_slot() = now_;
    const std::int64_t faults_at_start = thread_page_faults();
    // the thread's context switches and CPU time, read at every wake-up (one getrusage a tick): its
    // page faults from there, and the worst tick's (PeriodStats::worst) from the difference
    rusage usage_before{};
    bool have_usage = getrusage(RUSAGE_THREAD, &usage_before) == 0;
    float late_before[WorstTick::kHistory] = {};  // the latest ticks' lateness [us], a ring
    int ring_next = 0;
    stamp_parts_ = true;
    started_.store(1, std::memory_order_release);

    const std::int64_t period = std::int64_t(std::llround(1e9 / options_.rate_hz));
    const std::int64_t spin = std::int64_t(options_.spin_us * 1000.0);
    const double nominal_ms = double(period) * 1e-6;
    const std::int64_t origin = now_ns();
    std::int64_t due = origin + period, last_wake = origin;
    std::int64_t ready = origin;   // the end of the last tick's work (and bookkeeping)
    int cpu_ready = sched_getcpu();
    std::int64_t n = 0;
    std::uint32_t window = window_.load(std::memory_order_relaxed);
    while (running_.load(std::memory_order_relaxed)) {
        bool slept = false;
        std::int64_t woke = ready;  // from the sleep, where there was one
        if (due - spin > ready) {
            sleep_until_ns(due - spin);
            slept = true;
            woke = now_ns();
        }
        std::int64_t wake = woke;
        while (wake < due) {
            cpu_relax();
            wake = now_ns();
        }
        const int cpu_wake = sched_getcpu();
        rusage usage{};
        const bool usage_now = getrusage(RUSAGE_THREAD, &usage) == 0;
        stats_.add_period(double(wake - last_wake) * 1e-6, nominal_ms);
        const double late_ms = double(wake - due) * 1e-6;
        stats_.max_late_ms = std::max(stats_.max_late_ms, late_ms);
        if (const std::uint32_t w = window_.load(std::memory_order_relaxed); w != window) {
            window = w;
            stats_.window_max_late_ms = 0;
            stats_.worst = WorstTick{};
        }
        stats_.window_max_late_ms = std::max(stats_.window_max_late_ms, late_ms);
        if (late_ms > stats_.worst.late_ms) {
            WorstTick& w = stats_.worst;
            w.late_ms = late_ms;
            w.tick = ticks_.load(std::memory_order_relaxed) + 1;
            w.at_s = double(due - origin) * 1e-9;
            w.monotonic_s = double(wake) * 1e-9;
            w.spell_ms = double(wake - last_wake) * 1e-6;
            const bool after_a_tick = n > 0;  // the stamps are the tick before's
            w.before_us = after_a_tick ? double(stamps_[0] - last_wake) * 1e-3 : 0.0;
            w.read_us = after_a_tick ? double(stamps_[1] - stamps_[0]) * 1e-3 : 0.0;
            w.force_us = after_a_tick ? double(stamps_[2] - stamps_[1]) * 1e-3 : 0.0;
            w.write_us = after_a_tick ? double(stamps_[3] - stamps_[2]) * 1e-3 : 0.0;
            w.handoff_us = after_a_tick ? double(stamps_[4] - stamps_[3]) * 1e-3 : 0.0;
            w.after_us = after_a_tick ? double(ready - stamps_[4]) * 1e-3 : 0.0;
            w.slept = slept;
            w.sleep_late_us = slept ? double(woke - (due - spin)) * 1e-3 : 0.0;
            w.spin_us = double(wake - woke) * 1e-3;
            w.cpu_before = cpu_ready;
            w.cpu_after = cpu_wake;
            if (have_usage && usage_now) {
                w.voluntary_switches = usage.ru_nvcsw - usage_before.ru_nvcsw;
                w.involuntary_switches = usage.ru_nivcsw - usage_before.ru_nivcsw;
                const auto us = [](const rusage& u) {
                    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e6 + double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
                };
                w.ran_ms = (us(usage) - us(usage_before)) * 1e-3;
            } else {
                w.voluntary_switches = w.involuntary_switches = -1;
                w.ran_ms = -1;
            }
            for (int i = 0; i < WorstTick::kHistory; ++i) w.late_before_us[i] = late_before[(ring_next + i) % WorstTick::kHistory];
        }
        late_before[ring_next] = float(late_ms * 1000.0);
        ring_next = (ring_next + 1) % WorstTick::kHistory;
        if (usage_now) {
            usage_before = usage;
            have_usage = true;
            if (faults_at_start >= 0) stats_.page_faults = std::int64_t(usage.ru_minflt) + std::int64_t(usage.ru_majflt) - faults_at_start;
        }
        last_wake = wake;
        if (wake > due + period) {
            // woke after the next tick was due: count it, and do not run a burst of ticks to catch up
            ++stats_.missed_deadlines;
            due = wake;
        }
        tick(double(wake - origin) * 1e-9);
        const double work_us = double(stamps_[4] - wake) * 1e-3;
        if (work_us > stats_.max_tick_us) stats_.max_tick_us = work_us;
        if (++n % 100 == 0) {
            stats_out_.write_slot() = stats_;
            stats_out_.publish();
        }
        due += period;
        ready = now_ns();
        cpu_ready = sched_getcpu();
    }
    stamp_parts_ = false;
    if (const std::int64_t faults = thread_page_faults(); faults >= 0 && faults_at_start >= 0) stats_.page_faults = faults - faults_at_start;
    stats_out_.write_slot() = stats_;
    stats_out_.publish();
}

}  // namespace echosim::haptics

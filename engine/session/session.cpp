#include "session/session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <string>

namespace echosim::session {

Session::Session(const SessionOptions& options)
    : options_(options), compiled_(physics::compile_model(options.tissue ? tissue::build_tissue_model(leg_, *options.tissue, options.refine)
                                                                      : load_simulation_model(leg_, options.refine),
                                                       options.physics)),
      physics_(compiled_), mapping_(leg_), deformer_(leg_, compiled_->tissue), indentation_(*compiled_), patch_(leg_.patch().rest.vertices)
{
    echo::check_plane(options_.image);
    probe_.rest = leg_.probe_rest_pose(0.5f, 0.5f);
    view_.patch = &patch_;
    view_.echo = &echo_;
    view_.probe = probe_.face();
    if (options_.device) haptics_ = std::make_unique<haptics::HapticLoop>(physics_, options_.device, mapping_, options_.haptics);
    if (options_.clock == Clock::real_time) {
        physics_.start();
        if (haptics_) {
            haptics_->start();
            haptics_note_ = haptics_->priority_note();
        }
    }
}

Session::~Session() { stop(); }

void Session::stop()
{
    if (haptics_) haptics_->stop();  // first: it commands the physics
    physics_.stop();
}

void Session::place_probe(const ProbePlacement& placement)
{
    if (haptics_) throw std::logic_error("Session::place_probe: this session's probe is moved by its device (" + options_.device->capabilities().name + ")");
    if (!(placement.press_mm >= 0) || !std::isfinite(placement.press_mm))
        throw std::invalid_argument("probe press " + std::to_string(placement.press_mm) + " mm: must be finite and >= 0");
    // the physics would refuse it at the next advance, and the view would show a probe that is not simulated
    if (const std::string why = physics::probe_command_error(contact::probe_at(placement.face())); !why.empty())
        throw std::invalid_argument("probe pose: " + why);
    probe_ = placement;
}

void Session::place_probe_on_patch(float u, float v, double press_mm)
{
    place_probe({leg_.probe_rest_pose(u, v), press_mm});
}

void Session::advance(double dt)
{
    if (!(dt > 0)) throw std::invalid_argument("Session::advance by " + std::to_string(dt) + " s: must be > 0");
    if (haptics_) {
        if (options_.clock == Clock::lock_step) {
            const double end = time_ + dt, h = haptics_->period_s();
            while (haptic_time_ + h <= end + 1e-9) {
                haptic_time_ += h;
                haptics_->tick(haptic_time_);
                physics_.step_to(haptic_time_);
            }
            time_ = end;
        } else {
            time_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        }
        return;
    }
    // the press speed along the beam is what the contact's damping feels; sliding is left to the
    // contact's own velocity estimate
    const Pose face = probe_.face();
    const glm::dvec3 beam(face.axis_y());
    const double speed = (probe_.press_mm - sent_press_mm_) / dt;  // [mm/s]
    physics_.command(contact::probe_at(face, speed * Eigen::Vector3d(beam.x, beam.y, beam.z)));  // checked in place_probe
    sent_press_mm_ = probe_.press_mm;
    if (options_.clock == Clock::lock_step) {
        time_ += dt;
        physics_.step_to(time_);
    } else {
        time_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
}

SettleReport Session::press_and_settle(const Pose& rest, double press_mm, double settle_s)
{
    if (options_.clock != Clock::lock_step) throw std::logic_error("Session::press_and_settle needs the lock-step clock");
    constexpr double ramp = 0.1;  // [s]
    const double dt = options_.physics.time_step, start = time_;
    const auto window = std::max<std::size_t>(1, std::size_t(std::lround(kSettleWindowS / dt)));
    const int resets_before = physics_.latest().resets;
    std::deque<double> forces;  // the last two windows' forces, one a step
    SettleReport report;
    report.press_mm = press_mm;
    for (;;) {
        place_probe({rest, press_mm * std::min(1.0, (time_ + dt - start) / ramp)});
        advance(dt);
        const physics::SurfaceSnapshot& snap = physics_.latest();
        report.seconds = time_ - start;
        report.resets = snap.resets - resets_before;
        forces.push_back(snap.probe_force_N);
        if (forces.size() > 2 * window) forces.pop_front();
        if (report.seconds < std::max(settle_s, ramp) - 0.5 * dt || forces.size() < 2 * window) continue;
        const auto middle = forces.begin() + std::ptrdiff_t(window);
        const double before = std::accumulate(forces.begin(), middle, 0.0) / double(window);
        report.force_N = std::accumulate(middle, forces.end(), 0.0) / double(window);
        const auto [lo, hi] = std::minmax_element(middle, forces.end());
        report.ripple_N = 0.5 * (*hi - *lo);
        report.drift_N = std::abs(report.force_N - before);
        report.settled = report.resets == 0 && report.drift_N < settled_change_N(report.force_N);
        if (report.settled || report.seconds >= kMaxSettleS - 0.5 * dt) return report;
    }
}

SettleReport Session::press_to_force(const Pose& rest, double force_N)
{
    if (!(force_N > 0) || !std::isfinite(force_N))
        throw std::invalid_argument("probe force " + std::to_string(force_N) + " N: must be finite and > 0");
    auto settle = [&](double press) {
        const SettleReport r = press_and_settle(rest, press);
        if (!r.settled) throw std::runtime_error(not_settled_message(press, r));
        return r;
    };
    // the force grows with the press: bisect the press, each guess settled from the last
    double lo = 0, hi = kMaxPressMm;
    SettleReport r = settle(hi);
    if (r.force_N < force_N)
        throw std::invalid_argument("probe force " + std::to_string(force_N) + " N: out of reach, the tissue pushes back " +
                                    std::to_string(r.force_N) + " N at the deepest press (" + std::to_string(kMaxPressMm) + " mm)");
    for (int i = 0; i < 40; ++i) {
        r = settle(0.5 * (lo + hi));
        if (std::abs(r.force_N - force_N) <= 0.02 * force_N) break;
        (r.force_N < force_N ? lo : hi) = r.press_mm;
    }
    return r;
}

std::string not_settled_message(double press_mm, const SettleReport& r)
{
    char text[400];
    if (r.resets > 0)
        std::snprintf(text, sizeof text,
                      "the tissue simulation exploded under a %.2f mm press and was reset %d time(s) in %.1f s of simulated time: no "
                      "force to report",
                      press_mm, r.resets, r.seconds);
    else
        std::snprintf(text, sizeof text,
                      "the tissue has not settled under a %.2f mm press after %.1f s of simulated time: its mean push on the probe "
                      "(now %.3f N) still moved %.3f N in the last %.0f ms; the model's damping or stiffness is outside what a thigh "
                      "settles with",
                      press_mm, r.seconds, r.force_N, r.drift_N, 1000 * kSettleWindowS);
    return text;
}

const SessionView& Session::view()
{
    const physics::SurfaceSnapshot& snap = physics_.latest();
    if (snap.step != shown_step_) {
        deformer_.apply(snap.positions, patch_);
        shown_step_ = snap.step;
    }
    double press_mm = probe_.press_mm;
    const haptics::HapticSample* ticked = haptics_ ? &haptics_->latest() : nullptr;
    if (ticked && ticked->tick == 0) ticked = nullptr;  // before the loop's first tick the probe rests where it starts
    if (ticked) {
        const haptics::HapticSample& h = *ticked;
        const Eigen::Vector3d& p = h.face.position;
        const Eigen::Quaterniond& q = h.face.orientation;
        view_.probe = Pose{glm::vec3(float(p.x()), float(p.y()), float(p.z())), glm::quat(float(q.w()), float(q.x()), float(q.y()), float(q.z()))};
        // a device that places the probe over the skin says how far it presses; the others do not
        // (the image then takes the press from the tissue alone)
        press_mm = h.device.control == device::Control::surface ? h.device.surface.press_mm : 0.0;
        view_.haptic_force_N = h.force.along_N;
        view_.device_connected = h.device.connected;
    } else {
        view_.probe = probe_.face();
    }
    // the image's input from the same snapshot; before the first step the skin lies at rest
    echo_.face = view_.probe;
    echo_.time_s = snap.time;
    echo_.skin_pressure_kpa = kLinearProbe.face_pressure_kpa(snap.probe_force_N);
    // not touching: the image is the volume's own (which was taken with the tissue under its own
    // weight, as it lies now; the nodes' sag under gravity is no indentation)
    if (snap.positions.empty() || snap.contacts == 0)
        echo_.columns.clear();
    else
        indentation_.compute(view_.probe, press_mm, snap.positions, options_.image, echo_.columns);
    view_.press_mm = press_mm;
    view_.probe_force_N = snap.probe_force_N;
    view_.time_s = snap.time;
    view_.resets = snap.resets;
    return view_;
}

}  // namespace echosim::session

#include "session/session.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace echosim::session {

Session::Session(const SessionOptions& options)
    : options_(options), compiled_(physics::compile_model(load_simulation_model(leg_, options.refine), options.physics)),
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

void Session::press_and_settle(const Pose& rest, double press_mm, double settle_s)
{
    if (options_.clock != Clock::lock_step) throw std::logic_error("Session::press_and_settle needs the lock-step clock");
    constexpr double ramp = 0.1;  // [s]
    const double dt = options_.physics.time_step, start = time_;
    while (time_ - start < settle_s - 0.5 * dt) {
        place_probe({rest, press_mm * std::min(1.0, (time_ + dt - start) / ramp)});
        advance(dt);
    }
}

double Session::press_to_force(const Pose& rest, double force_N)
{
    if (!(force_N > 0) || !std::isfinite(force_N))
        throw std::invalid_argument("probe force " + std::to_string(force_N) + " N: must be finite and > 0");
    // the force grows with the press: bisect the press, each guess settled from the last
    double lo = 0, hi = kMaxPressMm, press = 0;
    press_and_settle(rest, hi);
    const double deepest = view().probe_force_N;
    if (deepest < force_N)
        throw std::invalid_argument("probe force " + std::to_string(force_N) + " N: out of reach, the tissue pushes back " +
                                    std::to_string(deepest) + " N at the deepest press (" + std::to_string(kMaxPressMm) + " mm)");
    for (int i = 0; i < 40; ++i) {
        press = 0.5 * (lo + hi);
        press_and_settle(rest, press);
        const double f = view().probe_force_N;
        if (std::abs(f - force_N) <= 0.02 * force_N) break;
        (f < force_N ? lo : hi) = press;
    }
    return press;
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
    echo_.skin_pressure_kpa = 1000.0 * snap.probe_force_N / (kLinearProbe.face_width_mm * kLinearProbe.face_thickness_mm);
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

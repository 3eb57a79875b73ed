#include "session/session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace echosim::session {

namespace {

using Clock_ = std::chrono::steady_clock;
double ms_since(Clock_::time_point t) { return std::chrono::duration<double, std::milli>(Clock_::now() - t).count(); }

// the tissue's parameters as the session runs them: the options' or the shipped thigh's, each
// sample's column deepened by tissue_depth_scale (SessionOptions)
tissue::TissueModel session_parameters(const SessionOptions& o)
{
    const double k = o.tissue_depth_scale;
    if (!std::isfinite(k) || k < 0.25 || k > 4.0)
        throw std::invalid_argument("SessionOptions::tissue_depth_scale " + std::to_string(k) + ": must be in [0.25, 4]");
    tissue::TissueModel fitted;
    if (o.tissue)
        fitted.samples = *o.tissue;
    else
        fitted = read_simulation_parameters();
    if (k != 1.0)
        for (double& b : fitted.samples.b) b *= k;
    return fitted;
}

std::unique_ptr<const scene::LegModel> start_leg(const SessionOptions& o)
{
    scene::LegOptions leg;
    leg.patch_centre = o.window_centre;
    return std::make_unique<const scene::LegModel>(leg);
}

// the shortest signed angle from a to b [rad]
float angle_from(float a, float b)
{
    constexpr float two_pi = 2.0f * std::numbers::pi_v<float>;
    float d = std::fmod(b - a, two_pi);
    if (d > 0.5f * two_pi) d -= two_pi;
    if (d < -0.5f * two_pi) d += two_pi;
    return d;
}

}  // namespace

Session::Session(const SessionOptions& options)
    : options_(options), fitted_(session_parameters(options)),
      home_mass_(build_simulation_model(scene::LegModel{}, fitted_, options.refine).mass), home_leg_(start_leg(options)), leg_(home_leg_.get()),
      compiled_(physics::compile_model(window_tissue(*leg_), options.physics)), physics_(compiled_),
      mapping_(*home_leg_), deformer_(std::make_unique<PatchDeformer>(*leg_, compiled_->tissue)), indentation_(*compiled_),
      patch_(leg_->patch().rest.vertices)
{
    echo::check_plane(options_.image);
    probe_.rest = leg_->probe_rest_pose(0.5f, 0.5f);
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
    stopped_ = true;
    if (haptics_) haptics_->stop();  // first: it commands the physics
    physics_.stop();
}

tissue::TissueModel Session::window_tissue(const scene::LegModel& leg) const
{
    // The fitted parameters hold per sample point, for the skin each point stands for on the home
    // patch, and the model puts a node's share of them on it whatever skin it covers. The window
    // has the home patch's size, but its grid is even in the leg's tube parameter, not in
    // millimetres: where the leg's stations are closer together (the hip, the knee) its rows are
    // closer, elsewhere farther apart, and the same forces would be spread over less or more skin
    // (a press at the groin pushed back 30 % less than at home). So each node's column is scaled by
    // the skin it carries here over what it carries at home, the ratio of its masses (which the
    // model makes from its share of the area): F_k(c) = w c / (b - a c) = c / (b/w - (a/w) c).
    // On the home patch w is exactly 1 and the model is the fitted one, bit for bit.
    tissue::TissueModel m = build_simulation_model(leg, fitted_, options_.refine);
    for (std::size_t k = 0; k < m.node_count(); ++k) {
        const double w = m.mass[k] / home_mass_[k];
        if (w == 1.0) continue;
        m.a[k] /= w;
        m.b[k] /= w;
    }
    return m;
}

Session::Window Session::build_window(std::unique_ptr<const scene::LegModel> leg) const
{
    Window w;
    w.compiled = physics::compile_model(window_tissue(*leg), options_.physics);
    w.rest = physics::make_state(*w.compiled);
    w.deformer = std::make_unique<PatchDeformer>(*leg, w.compiled->tissue);
    w.leg = std::move(leg);
    return w;
}

Pose Session::commanded_face()
{
    if (haptics_) {
        const haptics::HapticSample& h = haptics_->latest();
        if (h.tick == 0) return probe_.face();
        const Eigen::Vector3d& p = h.face.position;
        const Eigen::Quaterniond& q = h.face.orientation;
        return Pose{glm::vec3(float(p.x()), float(p.y()), float(p.z())), glm::quat(float(q.w()), float(q.x()), float(q.y()), float(q.z()))};
    }
    return probe_.face();
}

Session::WindowOffset Session::window_offset(const Pose& face) const
{
    const scene::LegModel& leg = *leg_;
    const scene::ExamPatch& w = leg.patch();
    const scene::LimbCoordinates centre{w.centre_t(), w.centre_theta()};
    const scene::LimbCoordinates at = leg.limb_coordinates(face.position);
    const glm::vec3 skin = leg.limb_point(at);
    WindowOffset o;
    // along: the rings are planes of constant z, the limb runs towards -z
    o.along_mm = double(leg.limb_point(centre).z - skin.z);
    // around: the skin's length at the face's ring from the window's centre angle to the face's
    const float d = angle_from(centre.theta, at.theta);
    constexpr int pieces = 8;
    double around = 0;
    for (int k = 0; k < pieces; ++k)
        around += double(glm::length(leg.limb_point({at.t, centre.theta + d * float(k + 1) / pieces}) -
                                     leg.limb_point({at.t, centre.theta + d * float(k) / pieces})));
    o.around_mm = d < 0 ? -around : around;
    o.height_mm = double(glm::dot(face.position - skin, leg.limb_normal(at)));
    return o;
}

bool Session::over_model(const Pose& face) const
{
    // each corner of the face inside the tissue grid, which covers the patch's (u, v) in
    // [1/16, 15/16] (tissue/sample_grid.hpp: the sample points' span)
    const scene::ExamPatch& w = leg_->patch();
    const double lo = tissue::SampleGrid::u(0), hi = tissue::SampleGrid::u(tissue::SampleGrid::rows - 1);
    const float half_x = float(kLinearProbe.face_width_mm / 2), half_z = float(kLinearProbe.face_thickness_mm / 2);
    for (float sx : {-1.0f, 1.0f})
        for (float sz : {-1.0f, 1.0f}) {
            const glm::vec3 corner = face.position + sx * half_x * face.axis_x() + sz * half_z * face.axis_z();
            const scene::LimbCoordinates c = leg_->limb_coordinates(corner);
            const double u = double(c.t - w.t0) / double(w.t1 - w.t0);
            const double v = double(angle_from(w.theta0, c.theta)) / double(w.theta1 - w.theta0);
            if (!(u >= lo && u <= hi && v >= lo && v <= hi)) return false;
        }
    return true;
}

bool Session::lifted(WindowOffset& o)
{
    if (!(physics_.latest().probe_force_N < kLiftedForceN)) return false;  // pressing: the window stays
    o = window_offset(commanded_face());
    return o.height_mm >= -kMaxInsideMm;
}

void Session::follow_probe()
{
    if (!options_.window_follows_probe || stopped_) return;
    WindowOffset o;
    if (!lifted(o) || o.height_mm > kHoverMm) return;
    const Pose face = commanded_face();
    if (std::abs(o.along_mm) <= kZoneAlongMm && std::abs(o.around_mm) <= kZoneAroundMm) return;
    move_to(leg_->limb_coordinates(face.position), true);
}

bool Session::move_window(scene::LimbCoordinates centre) { return move_to(centre, false); }

bool Session::move_to(scene::LimbCoordinates centre, bool if_lifted)
{
    // cheap first: a window that cannot come nearer (the limb's end) is not built again
    const scene::PatchCells cells = leg_->window_cells(centre);
    if (cells == leg_->patch().cells) return false;
    scene::LegOptions options = leg_->options();
    options.patch_centre = centre;
    if (if_lifted && options_.clock == Clock::real_time) {
        if (pending_.valid()) {
            if (pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;  // still building
            Window built = pending_.get();
            if (pending_cells_ == cells) return swap_in(std::move(built), true);
            // built for where the probe was: dropped, and built again for where it is
        }
        pending_cells_ = cells;
        pending_ = std::async(std::launch::async, [this, options] {
            // below the driver, the physics and the haptic loop on a machine short of cores
            setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 10);
            const auto start = Clock_::now();
            Window w = build_window(std::make_unique<const scene::LegModel>(options));
            w.build_ms = ms_since(start);
            return w;
        });
        return false;
    }
    const auto start = Clock_::now();
    Window next = build_window(std::make_unique<const scene::LegModel>(options));
    next.build_ms = ms_since(start);
    return swap_in(std::move(next), if_lifted);
}

bool Session::swap_in(Window next, bool if_lifted)
{
    const double build_ms = next.build_ms;
    const auto swap_start = Clock_::now();
    const bool real_time = options_.clock == Clock::real_time && !stopped_;  // a stopped session's physics stays stopped
    if (real_time) physics_.stop();
    // real time: the probe may have been pressed while the window was built; it keeps the old one
    WindowOffset o;
    if (if_lifted && !lifted(o)) {
        if (real_time) physics_.start();
        ++window_moves_.abandoned;
        return false;
    }
    physics_.replace_model(next.compiled, std::move(next.rest));
    if (real_time) physics_.start();
    const double swap_ms = ms_since(swap_start);

    // the driver's side: the deformer (which refers to the old leg) goes before the leg
    deformer_ = std::move(next.deformer);
    compiled_ = std::move(next.compiled);
    indentation_ = IndentationProfile(*compiled_);
    moved_leg_ = std::move(next.leg);
    leg_ = moved_leg_.get();
    patch_ = leg_->patch().rest.vertices;
    shown_step_ = -1;  // the next view() deforms the new patch from the newest snapshot
    ++window_serial_;
    WindowMoves& m = window_moves_;
    ++m.moves;
    m.last_build_ms = build_ms;
    m.max_build_ms = std::max(m.max_build_ms, build_ms);
    m.last_swap_ms = swap_ms;
    m.max_swap_ms = std::max(m.max_swap_ms, swap_ms);
    return true;
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
    place_probe({leg_->probe_rest_pose(u, v), press_mm});
}

void Session::await_device(std::chrono::microseconds at_most)
{
    if (!haptics_ || options_.clock != Clock::real_time || stopped_) return;
    const std::int64_t from = haptics_->ticks();
    const auto give_up = std::chrono::steady_clock::now() + at_most;
    // a tick is a millisecond: sleeping a tenth of one wastes little and burns no core
    while (haptics_->ticks() < from + 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(std::chrono::microseconds(100));
}

void Session::advance(double dt)
{
    if (!(dt > 0)) throw std::invalid_argument("Session::advance by " + std::to_string(dt) + " s: must be > 0");
    follow_probe();
    if (haptics_) {
        if (options_.clock == Clock::lock_step) {
            const double end = time_ + dt, h = haptics_->period_s();
            while (haptic_time_ + h <= end + 1e-9) {
                haptic_time_ += h;
                haptics_->tick(haptic_time_);
                // the physics may run ahead to the advance's end while the probe is clear of the
                // skin (PhysicsOptions::clear_stride): the ticks then read its "no contact" model
                physics_.step_to(haptic_time_, end);
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
        deformer_->apply(snap.positions, patch_);
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
    view_.in_contact = snap.contacts > 0;
    view_.over_model = over_model(view_.probe);
    view_.window_centre = {leg_->patch().centre_t(), leg_->patch().centre_theta()};
    view_.window_serial = window_serial_;
    view_.probe_force_N = snap.probe_force_N;
    view_.time_s = snap.time;
    view_.resets = snap.resets;
    return view_;
}

}  // namespace echosim::session

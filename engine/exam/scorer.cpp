#include "exam/scorer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>

#include "echo/phantom.hpp"
#include "echo/vein_course.hpp"

namespace echosim::exam {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// a press tilted beyond this is no longer an attempt at the station at all [deg]
constexpr double kVisitMaxAngleDeg = 45.0;

glm::dvec3 to_d(const glm::vec3& v) { return glm::dvec3(v); }

std::string format(const char* fmt, double a, double b = 0, double c = 0)
{
    char text[160];
    std::snprintf(text, sizeof text, fmt, a, b, c);
    return text;
}

bool vein_interior(std::uint8_t code)
{
    using echo::Tissue;
    return code == std::uint8_t(Tissue::vein_lumen) || code == std::uint8_t(Tissue::thrombus) ||
           code == std::uint8_t(Tissue::organised_thrombus);
}

// The pixels of `want` within the vessel's columns (its projection +- 1.5 radii across the array),
// anywhere along the beam: a vessel does not move sideways much under the probe, and the image's
// other vessels of the same kind lie beside it, not above or below it, at a station.
double vessel_area_mm2(const std::vector<std::uint8_t>& labels, const echo::ImagePlane& plane, const Pose& face, const VesselAxis& axis,
                       bool (*want)(std::uint8_t))
{
    if (axis.radius_mm <= 0 || labels.size() != plane.pixels()) return 0;
    const double lateral = glm::dot(axis.centre - to_d(face.position), to_d(face.axis_x()));
    const double half = 1.5 * axis.radius_mm;
    const double px = plane.pixel_x_mm(), py = plane.pixel_y_mm();
    const int c0 = std::max(0, int(std::floor((lateral - half + plane.width_mm / 2) / px)));
    const int c1 = std::min(int(plane.columns) - 1, int(std::ceil((lateral + half + plane.width_mm / 2) / px)));
    std::size_t n = 0;
    for (std::uint32_t r = 0; r < plane.rows; ++r)
        for (int c = c0; c <= c1; ++c)
            if (want(labels[std::size_t(r) * plane.columns + std::size_t(c)])) ++n;
    return double(n) * px * py;
}

}  // namespace

echo::EchoFrame unpressed(const echo::EchoFrame& pressed)
{
    echo::EchoFrame rest = pressed;
    rest.columns.clear();
    rest.skin_pressure_kpa = 0;
    return rest;
}

double station_image_depth_mm(const StationTruth& truth, const echo::EchoFrame& pressed, double trainee_depth_mm)
{
    const Pose rest = unpressed(pressed).face;
    const glm::dvec3 beam = glm::normalize(glm::dvec3(rest.axis_y()));
    const double far_mm = glm::dot(truth.vein.centre - glm::dvec3(rest.position), beam) + truth.vein.radius_mm + kStationImageMarginMm;
    double depth = std::clamp(trainee_depth_mm, kLinearProbe.image_depth_min_mm, kLinearProbe.image_depth_max_mm);
    while (depth < far_mm && depth + 10.0 <= kLinearProbe.image_depth_max_mm + 1e-9) depth += 10.0;
    return depth;
}

Compression measure_compression(const StationTruth& truth, const echo::EchoFrame& pressed, const echo::ImagePlane& plane,
                                const LabelImager& labels)
{
    return measure_compression(truth, pressed, plane, labels(unpressed(pressed)), labels(pressed));
}

Compression measure_compression(const StationTruth& truth, const echo::EchoFrame& pressed, const echo::ImagePlane& plane,
                                const std::vector<std::uint8_t>& at_rest, const std::vector<std::uint8_t>& at_press)
{
    // the unpressed plane has the same face (unpressed keeps it)
    auto artery = [](std::uint8_t code) { return code == std::uint8_t(echo::Tissue::artery_lumen); };
    Compression c;
    c.vein_rest_mm2 = vessel_area_mm2(at_rest, plane, pressed.face, truth.vein, vein_interior);
    c.vein_pressed_mm2 = vessel_area_mm2(at_press, plane, pressed.face, truth.vein, vein_interior);
    c.artery_rest_mm2 = vessel_area_mm2(at_rest, plane, pressed.face, truth.artery, artery);
    c.artery_pressed_mm2 = vessel_area_mm2(at_press, plane, pressed.face, truth.artery, artery);
    return c;
}

Scorer::Scorer(const Scenario& scenario, std::vector<StationTruth> truth)
    : scenario_(scenario), truth_(std::move(truth)), stations_(truth_.size())
{
}

Scorer::Geometry Scorer::geometry(const VesselAxis& axis, const Pose& face, const glm::dvec3& down, double depth_mm)
{
    Geometry g;
    if (axis.radius_mm <= 0) return g;
    const glm::dvec3 f = to_d(face.position), n = to_d(face.axis_z());
    const double dn = glm::dot(axis.direction, n);
    g.angle_deg = std::acos(std::min(1.0, std::abs(dn))) * kRadToDeg;
    if (std::abs(dn) < 1e-6) return g;  // the vessel runs in the plane: it does not cross it
    const double t = glm::dot(f - axis.centre, n) / dn;
    const glm::dvec3 q = axis.centre + t * axis.direction;
    // where the probe sits along the vessel: the vessel's point nearest the line from the face
    // along the station's way in (not where the probe's own tilted plane or beam crosses it deeper
    // down: a tilt stays at the station, to be judged oblique; nor the face's plain projection,
    // which a vessel diving under a thick fat layer shifts by the depth times the dive: under 38 mm
    // of fat the face over FV 22 cm projected within 10 mm of FV 24 cm's station, and was scored there)
    const glm::dvec3 w = f - axis.centre;
    const double across = glm::dot(down, axis.direction), parallel = 1 - across * across;
    g.along_mm = parallel > 1e-6 ? (glm::dot(axis.direction, w) - across * glm::dot(down, w)) / parallel : glm::dot(w, axis.direction);
    g.lateral_mm = glm::dot(q - f, to_d(face.axis_x()));
    const double depth = glm::dot(q - f, to_d(face.axis_y()));
    g.crosses = depth > 0 && depth < depth_mm;
    return g;
}

void Scorer::observe(const ExamSample& s)
{
    if (start_s_ < 0) start_s_ = s.time_s;
    end_s_ = s.time_s;
    const glm::dvec3 p = to_d(s.face.position);
    if (have_last_) path_mm_ += glm::length(p - last_position_);
    last_position_ = p;
    have_last_ = true;
    force_trace_.emplace_back(s.time_s, s.force_N);

    const bool contact = s.force_N > kContactForceN;
    const ScoringBands& bands = scenario_.bands;
    const bool pressing = s.force_N >= kPressingFraction * bands.adequate_force_N;
    current_.reset();
    double nearest_angle = 90;
    double nearest_along = 1e9;
    std::vector<Geometry>& geometries = geometries_;
    geometries.clear();
    // the probe is at one station at most: the nearest along the vein of those it is over
    std::optional<std::size_t> at;
    for (std::size_t i = 0; i < truth_.size(); ++i) {
        const Geometry g = geometry(truth_[i].vein, s.face, to_d(truth_[i].ideal_probe.axis_y()), s.image_depth_mm);
        geometries.push_back(g);
        if (!contact || !g.crosses || std::abs(g.along_mm) > kAlongToleranceMm) continue;
        if (std::abs(g.lateral_mm) <= bands.reach_mm && g.angle_deg <= kVisitMaxAngleDeg &&
            (!at || std::abs(g.along_mm) < std::abs(geometries[*at].along_mm)))
            at = i;
    }
    // the force held above the excessive limit at the station the probe is at (kExcessiveHoldS)
    for (std::size_t i = 0; i < stations_.size(); ++i) {
        Tracked& st = stations_[i];
        if (at != i) st.run.clear();
        if (at != i || !(s.force_N > bands.excessive_force_N)) {
            st.above_since_s = -1;
            continue;
        }
        if (st.above_since_s < 0) st.above_since_s = s.time_s;
        const double held = s.time_s - st.above_since_s;
        if (!st.excessive() && held >= kExcessiveHoldS - 1e-9) st.excessive_at_s = st.above_since_s;
        if (st.excessive()) st.excessive_held_s = std::max(st.excessive_held_s, held);
    }
    for (std::size_t i = 0; i < truth_.size(); ++i) {
        const StationTruth& t = truth_[i];
        Tracked& st = stations_[i];
        const Geometry& g = geometries[i];
        if (g.crosses && std::abs(g.along_mm) < nearest_along) nearest_along = std::abs(g.along_mm), nearest_angle = g.angle_deg;
        if (!contact || !g.crosses || std::abs(g.along_mm) > kAlongToleranceMm) continue;
        const bool over_vein = std::abs(g.lateral_mm) <= bands.reach_mm;
        if (over_vein && g.angle_deg <= kVisitMaxAngleDeg) {
            if (at != i) continue;  // over the vein, but nearer another station
            // at the station: the deepest press there is the one judged
            current_ = i;
            last_examined_ = i;
            if (g.angle_deg <= bands.transverse_deg && !st.reached) st.reached = true, st.reached_at_s = s.time_s;
            // the press held: the least force over the run's last kPressHeldS (the run's samples
            // from the last one at or before that long ago)
            st.run.emplace_back(s.time_s, s.force_N);
            while (st.run.size() > 1 && st.run[1].first <= s.time_s - kPressHeldS + 1e-9) st.run.erase(st.run.begin());
            if (s.time_s - st.run.front().first >= kPressHeldS - 1e-9) {
                double held = s.force_N;
                for (const auto& [time, force] : st.run) held = std::min(held, force);
                if (held > st.peak_force_N) {
                    st.peak_force_N = held;
                    st.peak_at_s = s.time_s;
                    st.at_peak = g;
                    if (s.echo) st.deepest = *s.echo, st.deepest_depth_mm = s.image_depth_mm;
                }
            }
            if (pressing && g.angle_deg > bands.transverse_deg && !st.oblique)
                st.oblique = true, st.oblique_at_s = s.time_s, st.oblique_angle_deg = g.angle_deg;
        } else if (!over_vein && pressing && !st.wrong_vessel) {
            // pressing beside the vein: over the artery or the great saphenous vein instead
            const glm::dvec3 down = to_d(t.ideal_probe.axis_y());
            const Geometry a = geometry(t.artery, s.face, down, s.image_depth_mm), v = geometry(t.saphenous, s.face, down, s.image_depth_mm);
            const double a_reach = std::max(bands.reach_mm, t.artery.radius_mm);
            const double v_reach = std::max(bands.reach_mm, t.saphenous.radius_mm);
            if (a.crosses && std::abs(a.lateral_mm) <= a_reach && std::abs(a.lateral_mm) < std::abs(g.lateral_mm))
                st.wrong_vessel = true, st.wrong_vessel_at_s = s.time_s, st.wrong_vessel_which = "the artery";
            else if (v.crosses && std::abs(v.lateral_mm) <= v_reach && std::abs(v.lateral_mm) < std::abs(g.lateral_mm))
                st.wrong_vessel = true, st.wrong_vessel_at_s = s.time_s, st.wrong_vessel_which = "the great saphenous vein";
            if (st.wrong_vessel) last_examined_ = i;
        }
    }
    if (contact && nearest_along < 1e8) {
        angle_sum_ += nearest_angle;
        angle_max_ = std::max(angle_max_, nearest_angle);
        ++angle_samples_;
    }
}

void Scorer::call(double time_s, Call c)
{
    if (!last_examined_) return;  // a call before any station is examined answers nothing
    Tracked& st = stations_[*last_examined_];
    st.call = c;
    st.call_at_s = time_s;
}

ExamReport Scorer::finish(const std::vector<std::optional<Compression>>& compression, const std::vector<std::string>& images) const
{
    const ScoringBands& bands = scenario_.bands;
    ExamReport r;
    r.case_id = scenario_.id;
    r.case_title = scenario_.title;
    r.protocol = protocol_name(scenario_.protocol);
    r.pass_mark = bands.pass_mark;
    r.adequate_force_N = bands.adequate_force_N;
    r.excessive_force_N = bands.excessive_force_N;
    r.course = {echo::kSfj_cm, echo::kBifurcation_cm, echo::kAdductorHiatus_cm, echo::kTrifurcation_cm};
    int points = 0, calls_right = 0, examined = 0;
    bool missed_thrombus = false, called_clot = false, all_collapsed_and_cleared = true;
    std::string clots_called;
    for (std::size_t i = 0; i < truth_.size(); ++i) {
        const StationTruth& t = truth_[i];
        const Tracked& st = stations_[i];
        StationResult s;
        s.name = t.name;
        s.segment = echo::segment_name(t.segment);
        s.s_cm = t.s_cm;
        s.reached = st.reached;
        s.reached_at_s = st.reached_at_s;
        s.offset_mm = st.peak_at_s >= 0 ? std::abs(st.at_peak.lateral_mm) : 0;
        s.angle_deg = st.peak_at_s >= 0 ? st.at_peak.angle_deg : 0;
        s.peak_force_N = st.peak_force_N;
        s.deepest_press_at_s = st.peak_at_s;
        if (i < compression.size() && compression[i]) {
            const Compression& c = *compression[i];
            s.lumen_rest_mm2 = c.vein_rest_mm2;
            s.lumen_pressed_mm2 = c.vein_pressed_mm2;
            s.collapse_ratio = c.vein_rest_mm2 > 0 ? c.vein_pressed_mm2 / c.vein_rest_mm2 : 1.0;
            s.artery_area_ratio = c.artery_rest_mm2 > 0 ? c.artery_pressed_mm2 / c.artery_rest_mm2 : 1.0;
        }
        s.thrombosed = t.thrombosed;
        s.call = st.call;
        const Call truth_call = t.thrombosed ? Call::not_compressible : Call::compressible;
        s.call_correct = st.call == truth_call;
        if (i < images.size()) s.image_png = images[i];

        const bool visited = st.peak_at_s >= 0;
        const bool measured = i < compression.size() && compression[i] && compression[i]->vein_rest_mm2 > 0;
        const bool walls_met = measured && s.collapse_ratio <= kWallsMetRatio;
        const bool enough = st.peak_force_N >= bands.adequate_force_N || walls_met;
        const bool adequate = visited && enough && !st.excessive() && st.at_peak.angle_deg <= bands.transverse_deg;
        points += int(st.reached) + int(adequate) + int(s.call_correct);
        if (visited || st.wrong_vessel) ++examined;
        if (s.call_correct) ++calls_right;

        // the errors, each once per station
        auto flag = [&](ErrorKind kind, double at_s, std::string detail) { r.errors.push_back({kind, t.name, at_s, std::move(detail)}); };
        if (st.wrong_vessel)
            flag(ErrorKind::wrong_vessel, st.wrong_vessel_at_s, "pressed " + st.wrong_vessel_which + " instead of the vein");
        else if (!visited)
            flag(ErrorKind::skipped_station, 0, "never reached");
        if (visited && st.oblique)
            flag(ErrorKind::oblique_plane, st.oblique_at_s,
                 format("plane %.0f deg from transverse (within %.0f expected)", st.oblique_angle_deg, bands.transverse_deg));
        if (visited && !enough)
            flag(ErrorKind::too_little_pressure, st.peak_at_s,
                 measured ? format("peak %.1f N, adequate from %.1f N; the walls did not meet (lumen %.0f %% of rest)", st.peak_force_N,
                                   bands.adequate_force_N, 100 * s.collapse_ratio)
                          : format("peak %.1f N, adequate from %.1f N", st.peak_force_N, bands.adequate_force_N));
        if (visited && st.excessive())
            flag(ErrorKind::excessive_force, st.excessive_at_s,
                 format("peak %.1f N, excessive above %.1f N, held there %.2f s", st.peak_force_N, bands.excessive_force_N, st.excessive_held_s));
        if (st.call != Call::none && !s.call_correct) {
            if (st.call == Call::not_compressible && t.mimic_nearby && !t.thrombosed)
                flag(ErrorKind::mimic_called_clot, st.call_at_s, "a lymph node beside the vein called a clot; the vein compresses");
            else
                flag(ErrorKind::wrong_call, st.call_at_s,
                     std::string("called ") + call_name(st.call) + ", the vein is " + (t.thrombosed ? "thrombosed" : "compressible"));
        } else if (st.call == Call::none && visited)
            flag(ErrorKind::wrong_call, st.peak_at_s, "no call made");

        if (t.thrombosed && st.call != Call::not_compressible) missed_thrombus = true;
        if (st.call == Call::not_compressible) {
            called_clot = true;
            clots_called += (clots_called.empty() ? "" : ", ") + t.name;
        }
        if (!(st.reached && adequate && st.call == Call::compressible)) all_collapsed_and_cleared = false;
        r.stations.push_back(std::move(s));
    }
    std::stable_sort(r.errors.begin(), r.errors.end(), [](const FlaggedError& a, const FlaggedError& b) { return a.time_s < b.time_s; });

    // the truth of the whole leg, not only of the stations: a two-point exam's stations may all be
    // clear over an isolated femoral clot
    r.dvt_present = !scenario_.anatomy.thrombi.empty() ||
                    std::any_of(truth_.begin(), truth_.end(), [](const StationTruth& t) { return t.thrombosed; });
    const int n = int(truth_.size());
    r.score = n > 0 ? double(points) / double(3 * n) : 0.0;
    r.passed = r.score >= bands.pass_mark && !missed_thrombus;
    if (called_clot)
        r.conclusion = "Non-compressible vein at " + clots_called + ": deep vein thrombosis";
    else if (all_collapsed_and_cleared && scenario_.protocol == Protocol::extended)
        r.conclusion = "Every station compressed: proximal deep vein thrombosis excluded";
    else if (all_collapsed_and_cleared)
        r.conclusion = std::string("Negative ") + protocol_name(scenario_.protocol) +
                       " exam: proximal deep vein thrombosis not excluded between its stations (an isolated femoral-vein clot "
                       "is missed by it); repeat in a week or perform an extended exam";
    else
        r.conclusion = "Incomplete exam: deep vein thrombosis not excluded";

    r.motion.duration_s = start_s_ >= 0 ? end_s_ - start_s_ : 0;
    r.motion.path_mm = path_mm_;
    r.motion.mean_angle_deg = angle_samples_ > 0 ? angle_sum_ / double(angle_samples_) : 0;
    r.motion.max_angle_deg = angle_max_;
    // OSAUS (1..5): systematic examination from the stations reached and adequately pressed,
    // interpretation from the calls, decision from the conclusion against the truth
    const double systematic = n > 0 ? double(points - calls_right) / double(2 * n) : 0;
    r.osaus.systematic_examination = 1 + 4 * systematic;
    r.osaus.interpretation = 1 + 4 * (n > 0 ? double(calls_right) / double(n) : 0);
    // a negative two- or three-point exam that says it does not exclude a clot between its stations
    // decides right even over one
    const bool cleared_limited = all_collapsed_and_cleared && scenario_.protocol != Protocol::extended;
    const bool decision_right = called_clot ? !missed_thrombus && r.dvt_present : all_collapsed_and_cleared && (!r.dvt_present || cleared_limited);
    r.osaus.decision = decision_right ? 5 : (examined > 0 ? 2 : 1);
    r.force_trace = force_trace_;
    return r;
}

}  // namespace echosim::exam

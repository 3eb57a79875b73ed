#include "echo/sweep.hpp"

#include <cmath>
#include <random>

#include <glm/gtc/quaternion.hpp>

namespace echosim::echo {

glm::dmat4 image_to_world(const Pose& pose, const ScanSpec& spec)
{
    const glm::dvec3 ax(pose.axis_x()), ay(pose.axis_y()), az(pose.axis_z()), o(pose.position);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(ax * spec.pixel_mm, 0.0);
    m[1] = glm::dvec4(ay * spec.pixel_mm, 0.0);
    m[2] = glm::dvec4(az, 0.0);
    // pixel centres: column c at x = (c + 0.5) px - width / 2, row r at y = (r + 0.5) px
    m[3] = glm::dvec4(o + (0.5 * spec.pixel_mm - spec.width_mm / 2) * ax + 0.5 * spec.pixel_mm * ay, 1.0);
    return m;
}

TrackedSweep make_sweep(const scene::LegModel& leg, const Medium& medium, const SweepOptions& o,
                        const std::function<void(int, int)>& progress)
{
    TrackedSweep out;
    out.sweep.width = o.spec.columns();
    out.sweep.height = o.spec.rows();
    std::mt19937_64 rng(o.seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    // tremor: first-order smoothed noise (a hand wanders, it does not jump)
    glm::dvec3 wander(0.0), tilt(0.0);
    const double keep = 0.9, kick = std::sqrt(1.0 - keep * keep);
    for (int f = 0; f < o.frames; ++f) {
        const float u = o.u_from + (o.u_to - o.u_from) * float(f) / float(std::max(1, o.frames - 1));
        Pose pose = leg.probe_rest_pose(u, o.v);
        for (int c = 0; c < 3; ++c) {
            wander[c] = keep * wander[c] + kick * o.tremor_mm * gauss(rng);
            tilt[c] = keep * tilt[c] + kick * o.tremor_deg * gauss(rng);
        }
        // wander within the skin's plane (not into it) and tilt about the probe's own axes
        pose.position += float(wander.x) * pose.axis_x() + float(wander.z) * pose.axis_z();
        const glm::dquat q = glm::angleAxis(glm::radians(tilt.x), glm::dvec3(1, 0, 0)) *
                             glm::angleAxis(glm::radians(tilt.z), glm::dvec3(0, 0, 1));
        pose.orientation = glm::normalize(pose.orientation * glm::quat(q));

        const BModeImage img = synthesize(medium, pose, o.spec);
        out.sweep.pixels.insert(out.sweep.pixels.end(), img.pixels.begin(), img.pixels.end());
        out.labels.insert(out.labels.end(), img.labels.begin(), img.labels.end());
        out.sweep.frames.push_back({f / o.frame_rate_hz, image_to_world(pose, o.spec), true});
        out.poses.push_back(pose);
        if (progress) progress(f + 1, o.frames);
    }
    return out;
}

}  // namespace echosim::echo

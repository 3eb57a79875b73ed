#include "echo/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include <glm/gtc/quaternion.hpp>

#include "core/fork_join.hpp"

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

std::vector<Pose> sweep_poses(const scene::LegModel& leg, const SweepOptions& o)
{
    std::vector<Pose> poses;
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
        poses.push_back(pose);
    }
    return poses;
}

namespace {

TrackedSweep empty_sweep(const SweepOptions& o)
{
    TrackedSweep out;
    out.sweep.width = o.spec.columns();
    out.sweep.height = o.spec.rows();
    return out;
}

}  // namespace

TrackedSweep make_sweep(const scene::LegModel& leg, const Medium& medium, const SweepOptions& o,
                        const std::function<void(int, int)>& progress)
{
    TrackedSweep out = empty_sweep(o);
    out.poses = sweep_poses(leg, o);
    for (int f = 0; f < o.frames; ++f) {
        const Pose& pose = out.poses[std::size_t(f)];
        const BModeImage img = synthesize(medium, pose, o.spec);
        out.sweep.pixels.insert(out.sweep.pixels.end(), img.pixels.begin(), img.pixels.end());
        out.labels.insert(out.labels.end(), img.labels.begin(), img.labels.end());
        out.sweep.frames.push_back({f / o.frame_rate_hz, image_to_world(pose, o.spec), true});
        if (progress) progress(f + 1, o.frames);
    }
    return out;
}

TrackedSweep make_sweep(const scene::LegModel& leg, SweepImager& imager, const SweepOptions& o,
                        const std::function<void(int, int)>& progress)
{
    TrackedSweep out = empty_sweep(o);
    out.poses = sweep_poses(leg, o);
    const std::size_t frame_bytes = std::size_t(out.sweep.width) * out.sweep.height, frames = out.poses.size();
    out.sweep.pixels.resize(frame_bytes * frames);
    out.labels.resize(frame_bytes * frames);
    const std::size_t batch = std::max<std::size_t>(1, imager.batch_frames());
    for (std::size_t f = 0; f < frames; f += batch) {
        const std::size_t n = std::min(batch, frames - f);
        imager.image(std::span(out.poses).subspan(f, n), out.sweep.pixels.data() + f * frame_bytes, out.labels.data() + f * frame_bytes);
        if (progress) progress(int(f + n), int(frames));
    }
    for (std::size_t f = 0; f < frames; ++f)
        out.sweep.frames.push_back({double(f) / o.frame_rate_hz, image_to_world(out.poses[f], o.spec), true});
    return out;
}

struct CpuSweepImager::Team {
    explicit Team(int parts) : threads(parts) {}
    ForkJoin threads;
};

CpuSweepImager::CpuSweepImager(std::shared_ptr<const io::Volume> labels, const ScanSpec& spec, int threads)
    : labels_(std::move(labels)), params_(bmode_params(spec, *labels_))
{
    const int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    team_ = std::make_unique<Team>(std::min(n, ForkJoin::kMaxParts));
}

CpuSweepImager::~CpuSweepImager() = default;

std::size_t CpuSweepImager::batch_frames() const { return std::size_t(team_->threads.parts()) * 2; }

void CpuSweepImager::image(std::span<const Pose> poses, std::uint8_t* pixels, std::uint8_t* labels)
{
    const std::size_t frame_bytes = std::size_t(params_.columns) * params_.rows;
    ForkJoin& team = team_->threads;
    team.run([&](int part) {
        for (std::size_t f = std::size_t(part); f < poses.size(); f += std::size_t(team.parts())) {
            const BModeImage img = synthesize(*labels_, params_, poses[f]);
            std::copy(img.pixels.begin(), img.pixels.end(), pixels + f * frame_bytes);
            std::copy(img.labels.begin(), img.labels.end(), labels + f * frame_bytes);
        }
    });
}

}  // namespace echosim::echo

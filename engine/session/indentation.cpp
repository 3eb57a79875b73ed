#include "session/indentation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

namespace echosim::session {

IndentationProfile::IndentationProfile(const physics::CompiledModel& model)
{
    const std::size_t n = model.node_count();
    rest_.resize(n);
    for (std::size_t i = 0; i < n; ++i) rest_[i] = glm::vec3(float(model.rest[3 * i]), float(model.rest[3 * i + 1]), float(model.rest[3 * i + 2]));
    // the grid's mean spacing along its rows
    double sum = 0;
    int count = 0;
    const int cols = model.grid.cols;
    for (std::size_t i = 0; i + 1 < n; ++i)
        if (cols > 1 && int((i + 1) % std::size_t(cols)) != 0) sum += glm::length(rest_[i + 1] - rest_[i]), ++count;
    if (count > 0) spacing_ = sum / count;
}

void IndentationProfile::compute(const Pose& face, double press_mm, std::span<const float> positions, const echo::ImagePlane& plane,
                                 std::vector<echo::ColumnProfile>& out) const
{
    if (positions.size() != 3 * rest_.size())
        throw std::invalid_argument("indentation: " + std::to_string(positions.size() / 3) + " node positions for a model of " +
                                    std::to_string(rest_.size()));
    const glm::quat to_probe = glm::conjugate(face.orientation);
    const float half_width = float(0.5 * plane.width_mm + 2 * spacing_);
    const float half_thickness = float(0.5 * kLinearProbe.face_thickness_mm + 2 * spacing_);
    near_.clear();
    for (std::size_t i = 0; i < rest_.size(); ++i) {
        const glm::vec3 r = to_probe * (rest_[i] - face.position);
        if (std::abs(r.x) > half_width || std::abs(r.z) > half_thickness) continue;
        const glm::vec3 p = to_probe * (glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]) - face.position);
        near_.emplace_back(r.x, r.z, r.y, p.y - r.y);
    }
    const float sx = float(0.6 * spacing_), sz = float(std::max(0.5 * kLinearProbe.face_thickness_mm, spacing_));
    // a column weighs the nodes within kReach lateral sigmas: beyond, a weight is under 1.6e-8 (the
    // sums below count from 1e-6), and the columns cost a few nodes each rather than all of them
    constexpr float kReach = 6.0f;
    std::sort(near_.begin(), near_.end(), [](const glm::vec4& a, const glm::vec4& b) { return a.x < b.x; });
    std::size_t first = 0, end = 0;
    out.resize(plane.columns);
    for (std::uint32_t c = 0; c < plane.columns; ++c) {
        const float x = float((c + 0.5) * plane.pixel_x_mm() - 0.5 * plane.width_mm);
        while (first < near_.size() && near_[first].x < x - kReach * sx) ++first;
        end = std::max(end, first);
        while (end < near_.size() && near_[end].x <= x + kReach * sx) ++end;
        double w_sum = 0, y_sum = 0, shift_sum = 0;
        for (std::size_t k = first; k < end; ++k) {
            const glm::vec4& n = near_[k];
            const float dx = (n.x - x) / sx, dz = n.y / sz;
            const double w = std::exp(-0.5 * double(dx * dx + dz * dz));
            w_sum += w, y_sum += w * n.z, shift_sum += w * n.w;
        }
        if (w_sum > 1e-6)
            out[c] = {float(y_sum / w_sum), float(shift_sum / w_sum)};
        else
            out[c] = {float(-press_mm), 0.0f};
    }
}

}  // namespace echosim::session

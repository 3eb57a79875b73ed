#include "echo/slice_cpu.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/matrix.hpp>

#include "echo/sweep.hpp"

namespace echosim::echo {
namespace {

// The two voxels a trilinear sample at index `p` (inside [0, size - 1]) blends along one axis, and
// the second one's weight. The pair is the last two voxels at the axis's far end; an axis one voxel
// long (a 2-D image, read as one slice) blends its voxel with itself, as the GPU's sampler clamps to
// the edge.
// (In the scalar of the caller, so each twin keeps its arithmetic.)
template <class T>
struct Taps {
    std::size_t at[2];
    T f;
};
template <class T>
Taps<T> taps(T p, std::size_t size)
{
    const std::size_t lo = std::min(std::size_t(p), size >= 2 ? size - 2 : 0);
    return {{lo, std::min(lo + 1, size - 1)}, p - T(lo)};
}

template <class Sample>
std::vector<std::uint8_t> slice(const io::Volume& v, const Pose& pose, const ScanSpec& spec, Sample&& sample)
{
    const glm::dmat4 to_world = image_to_world(pose, spec);
    const glm::dmat3 to_index = glm::inverse(v.directions);
    std::vector<std::uint8_t> out(std::size_t(spec.columns()) * spec.rows());
    for (std::uint32_t r = 0; r < spec.rows(); ++r)
        for (std::uint32_t c = 0; c < spec.columns(); ++c) {
            const glm::dvec3 world(to_world * glm::dvec4(c, r, 0, 1));
            out[std::size_t(r) * spec.columns() + c] = sample(to_index * (world - v.origin));
        }
    return out;
}

}  // namespace

std::vector<std::uint8_t> slice_grey(const io::Volume& v, const Pose& pose, const ScanSpec& spec)
{
    const std::uint8_t* d = v.as<std::uint8_t>();
    return slice(v, pose, spec, [&](const glm::dvec3& p) -> std::uint8_t {
        if (p.x < 0 || p.y < 0 || p.z < 0 || p.x > double(v.size[0] - 1) || p.y > double(v.size[1] - 1) || p.z > double(v.size[2] - 1))
            return 0;
        const auto x = taps(p.x, v.size[0]), y = taps(p.y, v.size[1]), z = taps(p.z, v.size[2]);
        double s = 0;
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    s += (dx ? x.f : 1 - x.f) * (dy ? y.f : 1 - y.f) * (dz ? z.f : 1 - z.f) * d[v.index(x.at[dx], y.at[dy], z.at[dz])];
        return std::uint8_t(std::clamp(s + 0.5, 0.0, 255.0));
    });
}

std::vector<std::uint8_t> slice_labels(const io::Volume& v, const Pose& pose, const ScanSpec& spec)
{
    const std::uint8_t* d = v.as<std::uint8_t>();
    return slice(v, pose, spec, [&](const glm::dvec3& p) -> std::uint8_t {
        const double i = std::round(p.x), j = std::round(p.y), k = std::round(p.z);
        if (i < 0 || j < 0 || k < 0 || i >= double(v.size[0]) || j >= double(v.size[1]) || k >= double(v.size[2])) return 0;
        return d[v.index(std::size_t(i), std::size_t(j), std::size_t(k))];
    });
}

SliceSample slice_sample(const kernels::SliceParams& p, std::span<const float> map, std::uint32_t c, std::uint32_t r)
{
    using namespace kernels;
    SliceSample s{pixel_x(c, p.pixel_x_mm, p.width_mm), vec2(pixel_y(r, p.pixel_y_mm), 0.0f), vec3(0.0f)};
    if ((p.flags & SLICE_WARPED) != 0u) {
        const MapTap t = map_tap(c, p);
        const std::size_t row_start = std::size_t(r) * p.map_columns;
        const vec2 left(map[2 * (row_start + t.left)], map[2 * (row_start + t.left) + 1]);
        const vec2 right(map[2 * (row_start + t.right)], map[2 * (row_start + t.right) + 1]);
        s.map = map_between(left, right, t.right_weight);
    }
    s.index = vec3(p.probe_to_index * vec4(s.x, s.map.x, 0.0f, 1.0f));
    return s;
}

std::uint8_t label_at(const io::Volume& labels, const glm::vec3& index)
{
    const glm::vec3 v = glm::floor(index + 0.5f);
    if (v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < float(labels.size[0]) && v.y < float(labels.size[1]) && v.z < float(labels.size[2]))
        return labels.as<std::uint8_t>()[labels.index(std::size_t(v.x), std::size_t(v.y), std::size_t(v.z))];
    return 0;
}

SliceOutput slice_stage_cpu(const io::Volume& volume, const io::Volume* labels, std::span<const float> map,
                            const kernels::SliceParams& p)
{
    using namespace kernels;
    const std::size_t n = std::size_t(p.columns) * p.rows;
    const bool warped = (p.flags & SLICE_WARPED) != 0u, want_labels = (p.flags & SLICE_LABELS) != 0u;
    if (warped && map.size() != 2 * std::size_t(p.map_columns) * p.rows) throw std::invalid_argument("slice: the deform map does not match the image");
    const std::uint8_t* g = volume.as<std::uint8_t>();
    const vec3 size(float(volume.size[0]), float(volume.size[1]), float(volume.size[2]));
    SliceOutput out;
    out.grey.resize(n);
    if (warped) out.gain.resize(n);
    if (want_labels) out.labels.assign(n, 0);
    for (std::uint32_t r = 0; r < p.rows; ++r)
        for (std::uint32_t c = 0; c < p.columns; ++c) {
            const std::size_t i = std::size_t(r) * p.columns + c;
            const SliceSample sample = slice_sample(p, map, c, r);
            if (warped) out.gain[i] = sample.map.y;
            const vec3 index = sample.index;
            if (inside_volume(index, size)) {
                const auto tx = taps(index.x, volume.size[0]), ty = taps(index.y, volume.size[1]), tz = taps(index.z, volume.size[2]);
                float s = 0;
                for (int dz = 0; dz < 2; ++dz)
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx)
                            s += (dx ? tx.f : 1 - tx.f) * (dy ? ty.f : 1 - ty.f) * (dz ? tz.f : 1 - tz.f) *
                                 float(g[volume.index(tx.at[dx], ty.at[dy], tz.at[dz])]);
                out.grey[i] = s;
            }
            if (want_labels && labels) out.labels[i] = label_at(*labels, index);
        }
    return out;
}

double normalised_cross_correlation(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                                    const std::vector<std::uint8_t>& mask)
{
    double sa = 0, sb = 0, n = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (mask.empty() || mask[k]) sa += a[k], sb += b[k], n += 1;
    if (n < 2) return 0;
    const double ma = sa / n, mb = sb / n;
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (mask.empty() || mask[k]) {
            ab += (a[k] - ma) * (b[k] - mb);
            aa += (a[k] - ma) * (a[k] - ma);
            bb += (b[k] - mb) * (b[k] - mb);
        }
    return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0;
}

double psnr_db(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, const std::vector<std::uint8_t>& mask)
{
    double se = 0, n = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (mask.empty() || mask[k]) {
            const double d = double(a[k]) - double(b[k]);
            se += d * d;
            n += 1;
        }
    return n > 0 && se > 0 ? 10.0 * std::log10(255.0 * 255.0 / (se / n)) : 99.0;
}

}  // namespace echosim::echo

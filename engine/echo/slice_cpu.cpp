#include "echo/slice_cpu.hpp"

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "echo/sweep.hpp"

namespace echosim::echo {
namespace {

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
        const std::size_t i = std::min(std::size_t(p.x), v.size[0] - 2), j = std::min(std::size_t(p.y), v.size[1] - 2),
                          k = std::min(std::size_t(p.z), v.size[2] - 2);
        const double fx = p.x - double(i), fy = p.y - double(j), fz = p.z - double(k);
        double s = 0;
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    s += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) *
                         d[v.index(i + std::size_t(dx), j + std::size_t(dy), k + std::size_t(dz))];
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

#include "echo/reconstruct.hpp"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace echosim::echo {
namespace {

// value, weight, label, label distance: the bytes one voxel costs while reconstructing
constexpr std::uint64_t kBytesPerVoxel = 4 + 4 + 1 + 4;

std::array<std::size_t, 3> voxels_for(const glm::dvec3& box, double voxel)
{
    return {std::size_t(std::ceil(box.x / voxel)) + 1, std::size_t(std::ceil(box.y / voxel)) + 1,
            std::size_t(std::ceil(box.z / voxel)) + 1};
}

}  // namespace

std::uint64_t reconstruction_bytes(const glm::dvec3& box, double voxel)
{
    const auto n = voxels_for(box, voxel);
    return std::uint64_t(n[0]) * n[1] * n[2] * kBytesPerVoxel;
}

SweepBox sweep_box(std::span<const glm::dmat4> frames, std::uint32_t width, std::uint32_t height)
{
    glm::dvec3 lateral(0.0), beam(0.0);
    for (const glm::dmat4& m : frames) {
        lateral += glm::normalize(glm::dvec3(m[0]));
        beam += glm::normalize(glm::dvec3(m[1]));
    }
    SweepBox box;
    if (frames.empty()) return box;
    const glm::dvec3 x = glm::normalize(lateral);
    const glm::dvec3 z = glm::normalize(glm::cross(x, beam));
    box.axes = glm::dmat3(x, glm::cross(z, x), z);
    const glm::dmat3 to_box = glm::transpose(box.axes);
    box.lo = glm::dvec3(1e300);
    box.hi = glm::dvec3(-1e300);
    for (const glm::dmat4& m : frames)
        for (double c : {0.0, double(width - 1)})
            for (double r : {0.0, double(height - 1)}) {
                const glm::dvec3 p = to_box * glm::dvec3(m * glm::dvec4(c, r, 0, 1));
                box.lo = glm::min(box.lo, p);
                box.hi = glm::max(box.hi, p);
            }
    return box;
}

SweepBox sweep_box(const io::Sweep& sweep)
{
    std::vector<glm::dmat4> transforms;
    for (const auto& f : sweep.frames)
        if (f.valid) transforms.push_back(f.image_to_reference);
    return sweep_box(transforms, sweep.width, sweep.height);
}

Reconstructor::Reconstructor(const glm::dvec3& lo, const glm::dvec3& hi, const ReconstructOptions& options, const glm::dmat3& axes)
    : options_(options), axes_(axes), lo_(lo)
{
    if (!(options.voxel_mm > 0) || !std::isfinite(options.voxel_mm))
        throw std::invalid_argument("voxel size must be a positive number of millimetres");
    const glm::dvec3 box = hi - lo;
    if (!(box.x > 0 && box.y > 0 && box.z > 0)) throw std::invalid_argument("the frames span an empty box");
    const std::uint64_t need = reconstruction_bytes(box, options.voxel_mm);
    if (need > options.memory_budget_bytes)
        throw std::runtime_error("a " + std::to_string(options.voxel_mm) + " mm voxel map of " + std::to_string(int(box.x)) + " x " +
                                 std::to_string(int(box.y)) + " x " + std::to_string(int(box.z)) + " mm needs " +
                                 std::to_string(need >> 20) + " MiB, over the memory budget of " +
                                 std::to_string(options.memory_budget_bytes >> 20) + " MiB (choose larger voxels or a larger budget)");
    size_ = voxels_for(box, options.voxel_mm);
    const std::size_t n = size_[0] * size_[1] * size_[2];
    value_.assign(n, 0.0f);
    weight_.assign(n, 0.0f);
    label_.assign(n, 0);
    label_distance_.assign(n, 1e9f);
}

std::uint64_t Reconstructor::memory_bytes() const { return voxel_count() * kBytesPerVoxel; }

void Reconstructor::insert(std::span<const std::uint8_t> pixels, std::span<const std::uint8_t> labels, std::uint32_t width,
                           std::uint32_t height, const glm::dmat4& image_to_world)
{
    if (pixels.size() != std::size_t(width) * height) throw std::invalid_argument("frame pixels do not match its size");
    const bool with_labels = !labels.empty();
    if (with_labels && labels.size() != pixels.size()) throw std::invalid_argument("frame labels do not match its size");
    // pixel (c, r) -> continuous voxel index: affine, so step along rows and columns
    const double inv = 1.0 / options_.voxel_mm;
    const glm::dmat3 to_map = glm::transpose(axes_);
    const glm::dvec3 p0 = (to_map * glm::dvec3(image_to_world * glm::dvec4(0, 0, 0, 1)) - lo_) * inv;
    const glm::dvec3 dc = to_map * glm::dvec3(image_to_world * glm::dvec4(1, 0, 0, 0)) * inv;
    const glm::dvec3 dr = to_map * glm::dvec3(image_to_world * glm::dvec4(0, 1, 0, 0)) * inv;
    const double nx = double(size_[0] - 1), ny = double(size_[1] - 1), nz = double(size_[2] - 1);
    const bool mean = options_.compounding == Compounding::mean;

    auto deposit = [&](std::size_t at, float v, float w) {
        if (mean) {
            value_[at] += w * v;
        } else {
            value_[at] = std::max(value_[at], v);
        }
        weight_[at] += w;
    };
    for (std::uint32_t r = 0; r < height; ++r) {
        glm::dvec3 p = p0 + double(r) * dr;
        for (std::uint32_t c = 0; c < width; ++c, p += dc) {
            if (p.x < 0 || p.y < 0 || p.z < 0 || p.x > nx || p.y > ny || p.z > nz) continue;
            const std::size_t k = std::size_t(r) * width + c;
            const float v = float(pixels[k]);
            const std::size_t i0 = std::size_t(p.x + 0.5), j0 = std::size_t(p.y + 0.5), k0 = std::size_t(p.z + 0.5);
            // a voxel's label is that of the nearest pixel that reached it
            auto label_voxel = [&](std::size_t vi, std::size_t vj, std::size_t vk) {
                if (!with_labels) return;
                const glm::dvec3 d = p - glm::dvec3(double(vi), double(vj), double(vk));
                const float dist = float(glm::dot(d, d));
                const std::size_t at = index(vi, vj, vk);
                if (dist < label_distance_[at]) label_distance_[at] = dist, label_[at] = labels[k];
            };
            if (options_.splat == Splat::nearest) {
                deposit(index(i0, j0, k0), v, 1.0f);
                label_voxel(i0, j0, k0);
                continue;
            }
            const std::size_t i = std::min(std::size_t(p.x), size_[0] - 2), j = std::min(std::size_t(p.y), size_[1] - 2),
                              kk = std::min(std::size_t(p.z), size_[2] - 2);
            const float fx = float(p.x - double(i)), fy = float(p.y - double(j)), fz = float(p.z - double(kk));
            for (int dz = 0; dz < 2; ++dz)
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx) {
                        const float w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
                        if (w <= 1e-4f) continue;
                        deposit(index(i + std::size_t(dx), j + std::size_t(dy), kk + std::size_t(dz)), v, w);
                        label_voxel(i + std::size_t(dx), j + std::size_t(dy), kk + std::size_t(dz));
                    }
        }
    }
}

std::uint64_t Reconstructor::filled_voxels() const
{
    return std::uint64_t(std::count_if(weight_.begin(), weight_.end(), [](float w) { return w > 0; }));
}

int Reconstructor::fill_holes(const std::function<void(double)>& progress)
{
    // turn sums into values first, so neighbours average values, not sums
    if (options_.compounding == Compounding::mean)
        for (std::size_t k = 0; k < value_.size(); ++k)
            if (weight_[k] > 0) value_[k] /= weight_[k], weight_[k] = 1.0f;
    const long sx = long(size_[0]), sy = long(size_[1]), sz = long(size_[2]);
    // visits the in-bounds 26 neighbours of voxel `at`: f(neighbour index, squared distance)
    auto for_neighbours = [&](std::size_t at, auto&& f) {
        const long i = long(at % size_[0]), j = long((at / size_[0]) % size_[1]), k = long(at / (size_[0] * size_[1]));
        for (long dz = -1; dz <= 1; ++dz)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dx = -1; dx <= 1; ++dx) {
                    const long x = i + dx, y = j + dy, z = k + dz;
                    if ((dx | dy | dz) == 0 || x < 0 || y < 0 || z < 0 || x >= sx || y >= sy || z >= sz) continue;
                    f(std::size_t((z * sy + y) * sx + x), float(dx * dx + dy * dy + dz * dz));
                }
    };
    // the front: empty voxels next to filled ones; each pass fills it and moves it one voxel out
    std::vector<std::uint8_t> queued(weight_.size(), 0);
    std::vector<std::size_t> front, next;
    for (std::size_t at = 0; at < weight_.size(); ++at)
        if (weight_[at] > 0)
            for_neighbours(at, [&](std::size_t n, float) {
                if (weight_[n] <= 0 && !queued[n]) queued[n] = 1, front.push_back(n);
            });
    std::vector<std::pair<float, std::uint8_t>> updates;
    const int max_passes = std::max(1, int(std::ceil(options_.max_fill_mm / options_.voxel_mm)));
    int pass = 0;
    for (; pass < max_passes && !front.empty(); ++pass) {
        updates.clear();
        for (std::size_t at : front) {
            double sum = 0, wsum = 0;
            float nearest = 1e9f;
            std::uint8_t label = 0;
            for_neighbours(at, [&](std::size_t n, float d2) {
                if (weight_[n] <= 0) return;
                const double w = 1.0 / std::sqrt(double(d2));  // distance-weighted
                sum += w * value_[n];
                wsum += w;
                if (d2 < nearest) nearest = d2, label = label_[n];
            });
            updates.push_back({float(sum / wsum), label});
        }
        // apply after the pass, so a pass does not run ahead along its own scan order
        next.clear();
        for (std::size_t q = 0; q < front.size(); ++q) {
            const std::size_t at = front[q];
            value_[at] = updates[q].first;
            weight_[at] = 1.0f;
            if (label_[at] == 0) label_[at] = updates[q].second;
        }
        for (std::size_t at : front)
            for_neighbours(at, [&](std::size_t n, float) {
                if (weight_[n] <= 0 && !queued[n]) queued[n] = 1, next.push_back(n);
            });
        front.swap(next);
        if (progress) progress(double(pass + 1) / max_passes);
    }
    return pass;
}

io::Volume Reconstructor::volume() const
{
    io::Volume v = io::make_volume(size_, io::VoxelType::uint8);
    v.origin = axes_ * lo_;
    v.directions = axes_ * options_.voxel_mm;
    std::uint8_t* out = v.as<std::uint8_t>();
    const bool mean = options_.compounding == Compounding::mean;
    for (std::size_t k = 0; k < value_.size(); ++k) {
        // mean: sums over weights (after fill_holes the weights are 1); max: the value itself
        const float x = weight_[k] > 0 ? (mean ? value_[k] / weight_[k] : value_[k]) : 0.0f;
        out[k] = std::uint8_t(std::clamp(x + 0.5f, 0.0f, 255.0f));
    }
    return v;
}

io::Volume Reconstructor::labels() const
{
    io::Volume v = io::make_volume(size_, io::VoxelType::uint8);
    v.origin = axes_ * lo_;
    v.directions = axes_ * options_.voxel_mm;
    std::copy(label_.begin(), label_.end(), v.as<std::uint8_t>());
    return v;
}

}  // namespace echosim::echo

#include "echo/reconstruct.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace echosim::echo {
namespace {

// value, weight, label, label distance: the bytes one voxel costs while reconstructing
constexpr std::uint64_t kBytesPerVoxel = 4 + 4 + 1 + 4;

template <class T>
void widen(const std::uint8_t* at, std::size_t count, float* out)
{
    for (std::size_t c = 0; c < count; ++c) {
        T v;
        std::memcpy(&v, at + sizeof(T) * c, sizeof(T));  // frames need not be aligned for T
        out[c] = float(v);
    }
}

// One row of a frame as float: the pasting works on values, whatever the file stored.
void row_values(const FramePixels& f, std::uint32_t row, std::vector<float>& out)
{
    const std::size_t w = f.width;
    const std::uint8_t* at = f.bytes.data() + std::size_t(row) * w * io::voxel_size(f.type);
    out.resize(w);
    switch (f.type) {
    case io::VoxelType::uint8: return widen<std::uint8_t>(at, w, out.data());
    case io::VoxelType::uint16: return widen<std::uint16_t>(at, w, out.data());
    case io::VoxelType::int16: return widen<std::int16_t>(at, w, out.data());
    case io::VoxelType::float32: return widen<float>(at, w, out.data());
    }
}

}  // namespace

VoxelGrid box_grid(const glm::dvec3& lo, const glm::dvec3& hi, double voxel_mm, const glm::dmat3& axes)
{
    if (!(voxel_mm > 0) || !std::isfinite(voxel_mm)) throw std::invalid_argument("voxel size must be a positive number of millimetres");
    const glm::dvec3 box = hi - lo;
    if (!(box.x > 0 && box.y > 0 && box.z > 0)) throw std::invalid_argument("the frames span an empty box");
    VoxelGrid g;
    g.axes = axes;
    g.origin = lo;
    g.spacing = glm::dvec3(voxel_mm);
    for (int a = 0; a < 3; ++a) {
        const double n = std::ceil(box[a] / voxel_mm) + 1;
        if (!(n < 1e15)) throw std::invalid_argument("the frames span a box too large to grid");
        g.size[std::size_t(a)] = std::size_t(n);
    }
    return g;
}

VoxelGrid plus_grid(std::span<const glm::dmat4> frames, std::uint32_t width, std::uint32_t height, const PixelRect& clip,
                    const glm::dvec3& spacing)
{
    if (frames.empty()) throw std::invalid_argument("no frame to grid");
    if (!(spacing.x > 0 && spacing.y > 0 && spacing.z > 0)) throw std::invalid_argument("the output spacing must be positive");
    // the clipped frame's corner pixels, as PLUS takes them (its clip corner is origin + size)
    const double x0 = std::max<double>(0, clip.x0), x1 = std::min<double>(width - 1.0, clip.x1);
    const double y0 = std::max<double>(0, clip.y0), y1 = std::min<double>(height - 1.0, clip.y1);
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const glm::dmat4& m : frames)
        for (double c : {x0, x1})
            for (double r : {y0, y1}) {
                const glm::dvec3 p(m * glm::dvec4(c, r, 0, 1));
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
    VoxelGrid g;
    g.spacing = spacing;
    for (int a = 0; a < 3; ++a) {
        g.origin[a] = std::floor(lo[a] / spacing[a]) * spacing[a];
        const double last = std::ceil((hi[a] - g.origin[a]) / spacing[a]);
        if (!(last < 1e15)) throw std::invalid_argument("the frames span a box too large to grid");
        g.size[std::size_t(a)] = std::size_t(last) + 1;
    }
    return g;
}

std::optional<PixelRect> clip_to_frame(const PixelRect& clip, std::uint32_t width, std::uint32_t height)
{
    if (width == 0 || height == 0 || clip.x0 >= width || clip.y0 >= height || clip.x1 < clip.x0 || clip.y1 < clip.y0)
        return std::nullopt;
    return PixelRect{clip.x0, clip.y0, std::min(clip.x1, width - 1), std::min(clip.y1, height - 1)};
}

namespace {

// The rectangle's corner pixels (their centres) in world.
std::array<glm::dvec3, 4> corners(const glm::dmat4& m, const PixelRect& rect)
{
    const double x0 = rect.x0, x1 = rect.x1, y0 = rect.y0, y1 = rect.y1;
    return {glm::dvec3(m * glm::dvec4(x0, y0, 0, 1)), glm::dvec3(m * glm::dvec4(x1, y0, 0, 1)),
            glm::dvec3(m * glm::dvec4(x0, y1, 0, 1)), glm::dvec3(m * glm::dvec4(x1, y1, 0, 1))};
}

}  // namespace

double sweep_thickness(std::span<const glm::dmat4> frames, const PixelRect& rect)
{
    if (frames.empty()) return 0;
    const glm::dmat4& first = frames.front();
    const glm::dvec3 cross = glm::cross(glm::dvec3(first[0]), glm::dvec3(first[1]));
    if (!(glm::length(cross) > 0)) return 0;  // a frame flattened to a line: no plane, no volume
    const glm::dvec3 n = glm::normalize(cross), o(first[3]);
    double most = 0;
    for (const glm::dmat4& m : frames)
        for (const glm::dvec3& p : corners(m, rect)) most = std::max(most, std::abs(glm::dot(n, p - o)));
    return most;
}

double frame_diagonal(std::span<const glm::dmat4> frames, const PixelRect& rect)
{
    double most = 0;
    for (const glm::dmat4& m : frames) {
        const auto c = corners(m, rect);
        most = std::max({most, glm::length(c[3] - c[0]), glm::length(c[2] - c[1])});
    }
    return most;
}

bool frames_reach(const VoxelGrid& grid, std::span<const glm::dmat4> frames, const PixelRect& rect)
{
    const glm::dmat3 to_map = glm::transpose(grid.axes);
    const glm::dvec3 half = 0.5 * grid.spacing;
    const glm::dvec3 lo = grid.origin - half;
    const glm::dvec3 hi = grid.origin + grid.spacing * glm::dvec3(double(grid.size[0] - 1), double(grid.size[1] - 1),
                                                                  double(grid.size[2] - 1)) + half;
    for (const glm::dmat4& m : frames) {
        glm::dvec3 a(std::numeric_limits<double>::max()), b(std::numeric_limits<double>::lowest());
        for (const glm::dvec3& p : corners(m, rect)) {
            a = glm::min(a, to_map * p);
            b = glm::max(b, to_map * p);
        }
        if (a.x <= hi.x && a.y <= hi.y && a.z <= hi.z && b.x >= lo.x && b.y >= lo.y && b.z >= lo.z) return true;
    }
    return false;
}

std::uint64_t VoxelGrid::voxel_count() const
{
    std::uint64_t n = 1;
    for (const std::size_t s : size)
        if (__builtin_mul_overflow(n, std::uint64_t(s), &n)) return std::numeric_limits<std::uint64_t>::max();
    return n;
}

std::uint64_t reconstruction_bytes(const VoxelGrid& grid)
{
    const std::uint64_t n = grid.voxel_count();
    return n > std::numeric_limits<std::uint64_t>::max() / kBytesPerVoxel ? std::numeric_limits<std::uint64_t>::max()
                                                                          : n * kBytesPerVoxel;
}

std::uint64_t reconstruction_bytes(const glm::dvec3& box, double voxel)
{
    return reconstruction_bytes(box_grid(glm::dvec3(0.0), box, voxel));
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
    : Reconstructor(box_grid(lo, hi, options.voxel_mm, axes), options)
{
}

Reconstructor::Reconstructor(const VoxelGrid& grid, const ReconstructOptions& options) : options_(options), grid_(grid), size_(grid.size)
{
    for (int a = 0; a < 3; ++a)
        if (!(grid.spacing[a] > 0) || !std::isfinite(grid.spacing[a]))
            throw std::invalid_argument("voxel size must be a positive number of millimetres");
    if (grid.voxel_count() == 0) throw std::invalid_argument("an empty voxel grid");
    const std::uint64_t need = reconstruction_bytes(grid);
    if (need > options.memory_budget_bytes) {
        const glm::dvec3 box = grid.spacing * glm::dvec3(double(size_[0] - 1), double(size_[1] - 1), double(size_[2] - 1));
        char spacing[64];
        std::snprintf(spacing, sizeof spacing, "%g x %g x %g mm", grid.spacing.x, grid.spacing.y, grid.spacing.z);
        throw std::runtime_error("a voxel map of " + std::string(spacing) + " voxels over " + std::to_string(std::llround(box.x)) +
                                 " x " + std::to_string(std::llround(box.y)) + " x " + std::to_string(std::llround(box.z)) +
                                 " mm needs " + std::to_string(need >> 20) + " MiB, over the memory budget of " +
                                 std::to_string(options.memory_budget_bytes >> 20) +
                                 " MiB (choose larger voxels or a larger budget)");
    }
    const std::size_t n = size_[0] * size_[1] * size_[2];
    value_.assign(n, 0.0f);
    weight_.assign(n, 0.0f);
    label_.assign(n, 0);
    label_distance_.assign(n, 1e9f);
}

std::uint64_t Reconstructor::memory_bytes() const { return reconstruction_bytes(grid_); }

void Reconstructor::insert(const FramePixels& frame, std::span<const std::uint8_t> labels, const glm::dmat4& image_to_world)
{
    const std::uint32_t width = frame.width, height = frame.height;
    if (frame.bytes.size() != std::size_t(width) * height * io::voxel_size(frame.type))
        throw std::invalid_argument("frame pixels do not match its size");
    const bool with_labels = !labels.empty();
    if (with_labels && labels.size() != std::size_t(width) * height) throw std::invalid_argument("frame labels do not match its size");
    if (width == 0 || height == 0) return;
    // pixel (c, r) -> continuous voxel index: affine, so step along rows and columns
    const glm::dvec3 inv = 1.0 / grid_.spacing;
    const glm::dmat3 to_map = glm::transpose(grid_.axes);
    const glm::dvec3 p0 = (to_map * glm::dvec3(image_to_world * glm::dvec4(0, 0, 0, 1)) - grid_.origin) * inv;
    const glm::dvec3 dc = to_map * glm::dvec3(image_to_world * glm::dvec4(1, 0, 0, 0)) * inv;
    const glm::dvec3 dr = to_map * glm::dvec3(image_to_world * glm::dvec4(0, 1, 0, 0)) * inv;
    const double nx = double(size_[0] - 1), ny = double(size_[1] - 1), nz = double(size_[2] - 1);
    const Compounding compounding = options_.compounding;
    const std::uint32_t c0 = options_.clip.x0, c1 = std::min(options_.clip.x1, width - 1);
    const std::uint32_t r0 = options_.clip.y0, r1 = std::min(options_.clip.y1, height - 1);
    const double threshold = options_.pixel_threshold;

    auto deposit = [&](std::size_t at, float v, float w) {
        switch (compounding) {
        case Compounding::mean:
            value_[at] += w * v;
            weight_[at] += w;
            return;
        case Compounding::max:
            value_[at] = weight_[at] > 0 ? std::max(value_[at], v) : v;
            weight_[at] = 1.0f;
            return;
        case Compounding::latest:
            value_[at] = v;
            weight_[at] = 1.0f;
            return;
        }
    };
    // maximum and latest take a trilinear corner only when it holds enough of the pixel, as PLUS
    const float min_weight = compounding == Compounding::mean ? 0.0f : 0.125f;
    for (std::uint32_t r = r0; r <= r1 && r0 <= r1; ++r) {
        row_values(frame, r, row_);
        glm::dvec3 p = p0 + double(r) * dr + double(c0) * dc;
        for (std::uint32_t c = c0; c <= c1; ++c, p += dc) {
            const float v = row_[c];
            if (v < threshold) continue;
            const std::size_t k = std::size_t(r) * width + c;
            // a voxel's label is that of the nearest pixel that reached it
            auto label_voxel = [&](std::size_t vi, std::size_t vj, std::size_t vk) {
                if (!with_labels) return;
                const glm::dvec3 d = p - glm::dvec3(double(vi), double(vj), double(vk));
                const float dist = float(glm::dot(d, d));
                const std::size_t at = index(vi, vj, vk);
                if (dist < label_distance_[at]) label_distance_[at] = dist, label_[at] = labels[k];
            };
            if (options_.splat == Splat::nearest) {
                // the voxel the pixel rounds to (halves up), when it is in the map
                const glm::dvec3 q = glm::floor(p + 0.5);
                if (q.x < 0 || q.y < 0 || q.z < 0 || q.x > nx || q.y > ny || q.z > nz) continue;
                const std::size_t i0 = std::size_t(q.x), j0 = std::size_t(q.y), k0 = std::size_t(q.z);
                deposit(index(i0, j0, k0), v, 1.0f);
                label_voxel(i0, j0, k0);
                continue;
            }
            // trilinear: only a pixel whose eight voxels are all in the map
            if (!(p.x >= 0 && p.y >= 0 && p.z >= 0 && p.x < nx && p.y < ny && p.z < nz)) continue;
            const std::size_t i = std::size_t(p.x), j = std::size_t(p.y), kk = std::size_t(p.z);
            const float fx = float(p.x - double(i)), fy = float(p.y - double(j)), fz = float(p.z - double(kk));
            for (int dz = 0; dz < 2; ++dz)
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx) {
                        const float w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
                        if (w <= min_weight) continue;
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
    const double finest = std::min({grid_.spacing.x, grid_.spacing.y, grid_.spacing.z});
    const int max_passes = std::max(1, int(std::ceil(options_.max_fill_mm / finest)));
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

io::Volume Reconstructor::empty_volume(io::VoxelType type) const
{
    io::Volume v = io::make_volume(size_, type);
    v.origin = grid_.axes * grid_.origin;
    v.directions = grid_.axes * glm::dmat3(grid_.spacing.x, 0, 0, 0, grid_.spacing.y, 0, 0, 0, grid_.spacing.z);
    return v;
}

io::Volume Reconstructor::volume() const
{
    io::Volume v = empty_volume(options_.output_type);
    const bool mean = options_.compounding == Compounding::mean;
    // mean: sums over weights (after fill_holes the weights are 1); max and latest: the value itself
    const auto value = [&](std::size_t k) { return weight_[k] > 0 ? (mean ? value_[k] / weight_[k] : value_[k]) : 0.0f; };
    switch (v.type) {
    case io::VoxelType::uint8: {
        std::uint8_t* out = v.as<std::uint8_t>();
        for (std::size_t k = 0; k < value_.size(); ++k) out[k] = std::uint8_t(std::clamp(value(k) + 0.5f, 0.0f, 255.0f));
        break;
    }
    case io::VoxelType::uint16: {
        std::uint16_t* out = v.as<std::uint16_t>();
        for (std::size_t k = 0; k < value_.size(); ++k) out[k] = std::uint16_t(std::clamp(value(k) + 0.5f, 0.0f, 65535.0f));
        break;
    }
    case io::VoxelType::int16: {
        std::int16_t* out = v.as<std::int16_t>();
        for (std::size_t k = 0; k < value_.size(); ++k)
            out[k] = std::int16_t(std::floor(std::clamp(value(k) + 0.5f, -32768.0f, 32767.0f)));
        break;
    }
    case io::VoxelType::float32: {
        float* out = v.as<float>();
        for (std::size_t k = 0; k < value_.size(); ++k) out[k] = value(k);
        break;
    }
    }
    return v;
}

io::Volume Reconstructor::labels() const
{
    io::Volume v = empty_volume(io::VoxelType::uint8);
    std::copy(label_.begin(), label_.end(), v.as<std::uint8_t>());
    return v;
}

}  // namespace echosim::echo

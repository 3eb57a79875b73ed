#include "app/volume_source.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include "app/bmode_imager.hpp"
#include "echo/case_volume.hpp"
#include "echo/echo_image_cpu.hpp"
#include "io/owned_temp.hpp"
#include "io/partial_file.hpp"
#include "io/volume_file.hpp"
#include "scene/leg.hpp"

namespace echosim::app {
namespace {

// Bump when the phantom, the B-mode model, the sweep or the reconstruction change what they make.
// v2: the B-mode model of the GPU kernels (issue 33); v3: the whole proximal vein course, its sweep
// and 0.4 mm voxels (issue 31); v4: specular echoes 10 to 18 dB over the speckle, the vein's wall
// denser than the muscle (fascial planes and vessel walls show; a closed vein's walls one line);
// v5: frames 95 mm deep, for the scanner's deepest image (70 mm) pressed in 25 mm
constexpr const char* kRecipe = "v5";

// A cached pair's folder while it is being written is NAME io::kPartialMarker PID-SIX.
using io::kPartialMarker;

// f(const T* voxels) with the volume's own voxel type.
template <class F>
void visit_voxels(const io::Volume& v, F&& f)
{
    switch (v.type) {
    case io::VoxelType::uint8: f(v.as<std::uint8_t>()); return;
    case io::VoxelType::uint16: f(v.as<std::uint16_t>()); return;
    case io::VoxelType::int16: f(v.as<std::int16_t>()); return;
    case io::VoxelType::float32: f(v.as<float>()); return;
    }
}

std::string number_text(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// An 8-bit volume (zeros) with the size, geometry and key/values of `v`.
io::Volume uint8_like(const io::Volume& v)
{
    io::Volume out = io::make_volume(v.size, io::VoxelType::uint8);
    out.directions = v.directions;
    out.origin = v.origin;
    out.key_values = v.key_values;
    return out;
}

// 8-bit grey for the image pipeline from a volume of another type: the range [lo, hi] of its finite
// voxels mapped linearly onto 0..255, rounded (non-finite voxels: 0). `rule` says so in words.
io::Volume to_grey(const io::Volume& v, std::string& rule)
{
    io::Volume grey = uint8_like(v);
    visit_voxels(v, [&](const auto* voxels) {
        const std::size_t n = v.voxel_count();
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        std::size_t non_finite = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = double(voxels[i]);
            if (!std::isfinite(x)) ++non_finite;
            else lo = std::min(lo, x), hi = std::max(hi, x);
        }
        const double scale = hi > lo ? 255.0 / (hi - lo) : 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = double(voxels[i]);
            grey.data[i] = std::isfinite(x) ? std::uint8_t(std::lround(std::clamp((x - lo) * scale, 0.0, 255.0))) : 0;
        }
        rule = std::string(io::to_string(v.type)) + " voxels ";
        if (non_finite == n) rule += "all non-finite: grey 0";
        else if (hi > lo) rule += number_text(lo) + ".." + number_text(hi) + " mapped linearly onto grey 0..255";
        else rule += "all " + number_text(lo) + ": grey 0";
        if (non_finite > 0 && non_finite < n) rule += ", " + std::to_string(non_finite) + " non-finite voxels as 0";
    });
    return grey;
}

// Tissue codes from a label map of another type, exact: every voxel must be an integer 0..255.
io::Volume to_codes(const io::Volume& v, const std::filesystem::path& path)
{
    io::Volume codes = uint8_like(v);
    visit_voxels(v, [&](const auto* voxels) {
        for (std::size_t i = 0; i < v.voxel_count(); ++i) {
            const double x = double(voxels[i]);
            if (!(x >= 0 && x <= 255 && x == std::floor(x))) {
                const std::size_t column = i % v.size[0], row = i / v.size[0] % v.size[1], slice = i / v.size[0] / v.size[1];
                throw std::invalid_argument(path.string() + ": labels: voxel (" + std::to_string(column) + ", " + std::to_string(row) +
                                            ", " + std::to_string(slice) + ") is " + number_text(x) + ", not a tissue code (an integer 0..255)");
            }
            codes.data[i] = std::uint8_t(x);
        }
    });
    return codes;
}

// the default volume's recipe, or its coarse one (`--coarse`)
echo::CaseVolumeOptions case_volume_options(bool coarse) { return coarse ? echo::coarse_case_volume_options() : echo::CaseVolumeOptions{}; }

}  // namespace

std::filesystem::path cache_folder()
{
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "echosim";
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "echosim";
    throw std::runtime_error("no cache folder: neither XDG_CACHE_HOME nor HOME is set");
}

std::filesystem::path case_volume_folder(echo::Case which, bool coarse)
{
    char voxel[32];
    std::snprintf(voxel, sizeof voxel, "-%gmm-", case_volume_options(coarse).voxel_mm);
    return cache_folder() / "volumes" / (std::string(echo::case_name(which)) + voxel + kRecipe);
}

VolumePair case_volume(echo::Case which, const std::function<void(const std::string&, double)>& progress, bool coarse)
{
    const std::string name = case_volume_folder(which, coarse).filename().string();
    const std::string what = "the " + std::string(echo::case_name(which)) + " case's volume";
    return cached_volume(name, what, [&] {
        const scene::LegModel leg;
        // imaged on the GPU when a device is at hand (the one ECHOSIM_GPU names, else the best)
        echo::CaseVolumeOptions options = case_volume_options(coarse);
        options.imager = bmode_imager_factory(gpu::ContextOptions::from_environment(), "echosim");
        return echo::make_case_volume(leg, which, options, progress);
    }, progress);
}

std::string cache_entry_name(const std::string& stem) { return stem + "-" + kRecipe; }

bool volume_cached(const std::string& name)
{
    const std::filesystem::path folder = cache_folder() / "volumes" / name;
    std::error_code ec;
    return std::filesystem::exists(folder / "volume.nrrd", ec) && std::filesystem::exists(folder / "labels.nrrd", ec);
}

VolumePair cached_volume(const std::string& name, const std::string& what, const std::function<echo::CaseVolume()>& make,
                         const std::function<void(const std::string&, double)>& progress)
{
    const std::filesystem::path folder = cache_folder() / "volumes" / name;
    const std::filesystem::path volume_file = folder / "volume.nrrd", labels_file = folder / "labels.nrrd";
    std::error_code ec;
    // pairs that runs killed while making them left half written (any case's, any recipe's)
    io::remove_stale(folder.parent_path(), kPartialMarker, std::nullopt, io::TempKind::folders);
    if (volume_cached(name)) {
        try {
            VolumePair pair = user_volume(volume_file, labels_file);
            pair.description = what + ", cached in " + folder.string();
            return pair;
        } catch (const std::exception& e) {
            // a damaged cache is only a cache: say so and make it anew
            if (progress) progress(std::string("the cached volume is unreadable (") + e.what() + "), making it anew", 0.0);
            std::filesystem::remove_all(folder, ec);
        }
    }

    echo::CaseVolume made = make();
    // the pair into a folder of its own (locked while this run lives: io/owned_temp.hpp), renamed
    // into place whole
    std::filesystem::create_directories(folder.parent_path(), ec);
    if (ec) throw std::runtime_error("cannot create the volume cache folder " + folder.parent_path().string() + ": " + ec.message());
    io::OwnedTemp partial;
    try {
        partial = io::create_owned_folder(folder.parent_path(), name, kPartialMarker);
    } catch (const std::system_error& e) {
        throw std::runtime_error(std::string("cannot write the volume cache: ") + e.what());
    }
    try {
        io::write_nrrd(partial.path / "volume.nrrd", made.volume, true);
        io::write_nrrd(partial.path / "labels.nrrd", made.labels, true);
    } catch (...) {
        std::filesystem::remove_all(partial.path, ec);
        ::close(partial.fd);
        throw;
    }
    std::error_code moved;
    std::filesystem::rename(partial.path, folder, moved);
    if (moved) std::filesystem::remove_all(partial.path, ec);  // another run cached it first: theirs is as good
    ::close(partial.fd);
    if (moved && !std::filesystem::exists(volume_file))
        throw std::runtime_error("cannot move the volume into the cache at " + folder.string() + ": " + moved.message());
    VolumePair pair{std::make_shared<io::Volume>(std::move(made.volume)), std::make_shared<io::Volume>(std::move(made.labels)),
                    what + ", made and cached in " + folder.string()};
    return pair;
}

VolumePair user_volume(const std::filesystem::path& volume, const std::filesystem::path& labels)
{
    VolumePair pair;
    auto v = std::make_shared<io::Volume>(io::read_volume(volume));
    std::string rule;
    if (v->type != io::VoxelType::uint8) *v = to_grey(*v, rule);
    std::shared_ptr<io::Volume> l;
    if (!labels.empty()) {
        l = std::make_shared<io::Volume>(io::read_volume(labels));
        if (l->type != io::VoxelType::uint8) *l = to_codes(*l, labels);
    }
    try {
        echo::check_volumes(*v, l.get());
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument((labels.empty() ? volume.string() : volume.string() + " with " + labels.string()) + ": " + e.what());
    }
    pair.volume = std::move(v);
    pair.labels = std::move(l);
    pair.description = volume.string() + (rule.empty() ? "" : " (" + rule + ")") +
                       (labels.empty() ? " (no labels: linear deformation)" : " with labels " + labels.string());
    return pair;
}

}  // namespace echosim::app

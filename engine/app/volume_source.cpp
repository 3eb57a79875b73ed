#include "app/volume_source.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

#include "echo/case_volume.hpp"
#include "echo/echo_image_cpu.hpp"
#include "scene/leg.hpp"

namespace echosim::app {
namespace {

// Bump when the phantom, the B-mode model, the sweep or the reconstruction change what they make.
constexpr const char* kRecipe = "v1";

}  // namespace

std::filesystem::path cache_folder()
{
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "echosim";
    if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "echosim";
    throw std::runtime_error("no cache folder: neither XDG_CACHE_HOME nor HOME is set");
}

VolumePair case_volume(echo::Case which, const std::function<void(const std::string&, double)>& progress)
{
    const std::string name = std::string(echo::case_name(which)) + "-0.3mm-" + kRecipe;
    const std::filesystem::path folder = cache_folder() / "volumes" / name;
    const std::filesystem::path volume_file = folder / "volume.nrrd", labels_file = folder / "labels.nrrd";
    std::error_code ec;
    if (std::filesystem::exists(volume_file) && std::filesystem::exists(labels_file)) {
        try {
            VolumePair pair = user_volume(volume_file, labels_file);
            pair.description = "the " + std::string(echo::case_name(which)) + " case's volume, cached in " + folder.string();
            return pair;
        } catch (const std::exception& e) {
            // a damaged cache is only a cache: say so and make it anew
            if (progress) progress(std::string("the cached volume is unreadable (") + e.what() + "), making it anew", 0.0);
            std::filesystem::remove_all(folder, ec);
        }
    }

    const scene::LegModel leg;
    echo::CaseVolume made = echo::make_case_volume(leg, which, {}, progress);
    // the pair into a folder of its own, renamed into place whole
    const std::filesystem::path partial = folder.parent_path() / (name + ".partial-" + std::to_string(::getpid()));
    std::filesystem::create_directories(partial, ec);
    if (ec) throw std::runtime_error("cannot create the volume cache folder " + partial.string() + ": " + ec.message());
    try {
        io::write_nrrd(partial / "volume.nrrd", made.volume, true);
        io::write_nrrd(partial / "labels.nrrd", made.labels, true);
    } catch (...) {
        std::filesystem::remove_all(partial, ec);
        throw;
    }
    std::filesystem::rename(partial, folder, ec);
    if (ec) {
        std::filesystem::remove_all(partial);  // another run cached it first: theirs is as good
        if (!std::filesystem::exists(volume_file)) throw std::runtime_error("cannot move the volume into the cache at " + folder.string() + ": " + ec.message());
    }
    VolumePair pair{std::make_shared<io::Volume>(std::move(made.volume)), std::make_shared<io::Volume>(std::move(made.labels)),
                    "the " + std::string(echo::case_name(which)) + " case's volume, made and cached in " + folder.string()};
    return pair;
}

std::function<void(const std::string&, double)> terminal_progress(const char* command)
{
    return [command, last = std::string(), percent = -1](const std::string& stage, double done) mutable {
        const int now = int(100 * done);
        if (stage == last && now == percent) return;
        last = stage;
        percent = now;
        std::fprintf(stderr, "\r%s: making the default volume (once; it is cached): %s %3d %%\033[K", command, stage.c_str(), now);
    };
}

VolumePair user_volume(const std::filesystem::path& volume, const std::filesystem::path& labels)
{
    VolumePair pair;
    auto v = std::make_shared<io::Volume>(io::read_nrrd(volume));
    std::shared_ptr<io::Volume> l;
    if (!labels.empty()) l = std::make_shared<io::Volume>(io::read_nrrd(labels));
    try {
        echo::check_volumes(*v, l.get());
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument((labels.empty() ? volume.string() : volume.string() + " with " + labels.string()) + ": " + e.what());
    }
    pair.volume = std::move(v);
    pair.labels = std::move(l);
    pair.description = volume.string() + (labels.empty() ? " (no labels: linear deformation)" : " with labels " + labels.string());
    return pair;
}

}  // namespace echosim::app

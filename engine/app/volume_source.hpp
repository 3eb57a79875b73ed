// Where the echographic image's volume comes from: the user's own (`--volume F [--labels F]`, NRRD
// or MetaImage, for example one reconstructed from their own PLUS recording), or the default case's,
// made on first use (the phantom imaged and reconstructed: echo/case_volume.hpp, about a minute)
// and kept in the user's cache ($XDG_CACHE_HOME/echosim, else ~/.cache/echosim), so later runs
// start at once. A cached pair is written into a folder of its own under a temporary name and
// renamed into place whole, so a run interrupted while making it leaves no half pair that a later
// run would take, and the half-written folder it leaves (NAME.partial-PID-SIX, io/owned_temp.hpp)
// is removed by the next run once its owner is gone; the folder's name carries the recipe's
// version, so a changed recipe is remade.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "echo/case_volume.hpp"
#include "echo/phantom.hpp"
#include "io/nrrd.hpp"

namespace echosim::app {

struct VolumePair {
    std::shared_ptr<const io::Volume> volume;
    std::shared_ptr<const io::Volume> labels;  // null: none (the paper's linear deformation)
    std::string description;                   // for messages: where it came from
};

// The cache folder: $XDG_CACHE_HOME/echosim, else $HOME/.cache/echosim. Throws std::runtime_error
// when neither variable is set.
std::filesystem::path cache_folder();

// The folder in the cache that holds a case's default volume and labels (volume.nrrd, labels.nrrd),
// or its coarse one (echo::coarse_case_volume_options): named by the case, the voxel and the recipe.
std::filesystem::path case_volume_folder(echo::Case which, bool coarse = false);

// The default volume of a case, from the cache or made now (telling `progress` what it does and
// how far it is, 0..1) and cached. Throws std::runtime_error naming the folder when the cache
// cannot be written, io::NrrdError naming the file when a cached one cannot be read.
VolumePair case_volume(echo::Case which, const std::function<void(const std::string& stage, double done)>& progress,
                       bool coarse = false);

// The pair cached under `name` (a folder in the cache's volumes/: cache_entry_name gives one that
// carries the recipe's version), or made by `make` now and cached, whole or not at all. `what`
// names it in the description. The case volume above is one such entry; an exam's case is another.
VolumePair cached_volume(const std::string& name, const std::string& what, const std::function<echo::CaseVolume()>& make,
                         const std::function<void(const std::string& stage, double done)>& progress);
// Whether the pair `name` is in the cache (cached_volume would read it, not make it).
bool volume_cached(const std::string& name);
// `stem` with the version of the recipe that makes volumes (bumped when what they hold changes).
std::string cache_entry_name(const std::string& stem);

// What the commands that make the default volume on first use put before its progress's stage,
// after their own name (TerminalProgress's lead: "echosim run: " + kCaseVolumeProgress).
inline constexpr const char* kCaseVolumeProgress = "making the default volume (once; it is cached): ";

// The user's volume and labels (empty path: none), NRRD or MetaImage (io::read_volume), read and
// checked (labels on the volume's grid). The image pipeline reads 8-bit grey and 8-bit tissue codes:
// - a volume of another type (16-bit, signed or float, e.g. reconstructed from a 16-bit recording)
//   is mapped linearly from the range of its finite voxels, min..max, onto grey 0..255 (rounded;
//   non-finite voxels 0), and the description says so with the numbers, e.g. "V.mha (unsigned short
//   voxels 12..3981 mapped linearly onto grey 0..255)", so the one line a command prints about its
//   volume states the rule; for another window, convert the volume to 8 bits before;
// - labels of another type (Slicer often writes label maps as short) are kept exactly when every
//   voxel is an integer 0..255, else refused naming the first voxel that is not.
// Throws io::NrrdError, io::MetaImageError, io::VolumeFileError or std::invalid_argument naming the
// file.
VolumePair user_volume(const std::filesystem::path& volume, const std::filesystem::path& labels);

}  // namespace echosim::app

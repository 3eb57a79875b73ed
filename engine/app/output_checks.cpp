#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "app/commands.hpp"
#include "io/owned_temp.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"
#include "scene/leg.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::app {
namespace {

// the folder a path names a file in ("." for a bare name)
std::filesystem::path folder_of(const std::filesystem::path& path) { return path.has_parent_path() ? path.parent_path() : "."; }

// What write_together names its staging folders: MARKER PID-SIX, beside the outputs.
constexpr const char* kStagingMarker = ".echosim-writing-";

// The longest path a write of `path` hands the system: the file's temporary inside a staging folder.
std::size_t longest_written_path(const std::filesystem::path& path)
{
    const std::string staging = std::string(kStagingMarker) + std::string(io::kOwnedTailMax, 'x');
    const std::string partial = io::partial_head(path.filename().string()) + io::kPartialMarker + std::string(io::kOwnedTailMax, 'x');
    return (folder_of(path) / staging / partial).string().size();
}

// Whether two paths name the same file: the same file when both exist (links and hard links
// followed), else the same place once `.`, `..` and the links of the folders above are resolved.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        const bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    const auto place = [](const fs::path& p) {
        std::error_code e;
        const fs::path absolute = fs::absolute(p, e).lexically_normal();
        const fs::path resolved = fs::weakly_canonical(absolute, e);
        return e ? absolute : resolved;
    };
    return place(a) == place(b);
}

}  // namespace

bool output_path_usable(const char* command, const char* option, const std::filesystem::path& path)
{
    const std::filesystem::path parent = folder_of(path);
    if (!std::filesystem::is_directory(parent)) {
        std::fprintf(stderr, "echosim %s: %s %s: folder %s does not exist\n", command, option, path.c_str(), parent.c_str());
        return false;
    }
    if (io::text::is_special_file(path)) {
        std::fprintf(stderr, "echosim %s: %s %s: %s; refusing to replace it\n", command, option, path.c_str(), io::text::not_regular_file);
        return false;
    }
    // a name too long for the file system would fail only at the end, after the work: the name itself
    // (NAME_MAX: a derived name such as OUT.labels.nrrd can pass it where OUT did not), or the whole
    // path once the staging folder and the temporary's suffix are added (PATH_MAX)
    const long name_max = ::pathconf(parent.c_str(), _PC_NAME_MAX);
    const std::size_t name_limit = name_max > 0 ? std::size_t(name_max) : NAME_MAX;
    if (path.filename().string().size() > name_limit) {
        std::fprintf(stderr, "echosim %s: %s %s: a file name of %zu bytes; the folder allows %zu\n", command, option, path.c_str(),
                     path.filename().string().size(), name_limit);
        return false;
    }
    if (const std::size_t longest = longest_written_path(path); longest >= PATH_MAX) {
        std::fprintf(stderr, "echosim %s: %s %s: a path too long to write (%zu bytes with its temporary's; at most %d)\n", command,
                     option, path.c_str(), longest, PATH_MAX - 1);
        return false;
    }
    // a read-only folder (or file system) would fail only at the end, after the work
    if (::access(parent.c_str(), W_OK) != 0) {
        std::fprintf(stderr, "echosim %s: %s %s: cannot write in folder %s: %s\n", command, option, path.c_str(), parent.c_str(),
                     std::generic_category().message(errno).c_str());
        return false;
    }
    return true;
}

bool outputs_distinct(const char* command, const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs)
{
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        if (outputs[i].path.empty()) continue;
        for (std::size_t j = 0; j < i; ++j) {
            if (outputs[j].path.empty() || !same_file(outputs[i].path, outputs[j].path)) continue;
            std::fprintf(stderr, "echosim %s: %s %s and %s %s name the same file: give each output a file of its own\n", command,
                         outputs[j].option.c_str(), outputs[j].path.c_str(), outputs[i].option.c_str(), outputs[i].path.c_str());
            return false;
        }
        for (const NamedPath& in : inputs) {
            if (in.path.empty() || !same_file(outputs[i].path, in.path)) continue;
            std::fprintf(stderr, "echosim %s: %s %s names the same file as %s %s, which writing it would replace: write elsewhere\n",
                         command, outputs[i].option.c_str(), outputs[i].path.c_str(), in.option.c_str(), in.path.c_str());
            return false;
        }
    }
    return true;
}

bool read_model_option(const char* command, const std::filesystem::path& file, std::optional<tissue::SampleParameters>& tissue)
{
    if (file.empty()) return true;
    try {
        const tissue::TissueModel read = tissue::read_tissue_model(file);
        tissue::check_derived_fields(file, read, tissue::build_tissue_model(scene::LegModel{}, read.samples, read.refine));
        tissue = read.samples;
    } catch (const tissue::ModelFileError& e) {
        std::fprintf(stderr, "echosim %s: --model: %s\n", command, e.what());
        return false;
    }
    return true;
}

void write_together(const std::vector<std::filesystem::path>& paths,
                    const std::function<void(std::size_t, const std::filesystem::path&)>& write)
{
    namespace fs = std::filesystem;
    struct Staging {
        io::OwnedTemp temp;  // locked while this process lives: a killed run's is removed by the next
        ~Staging()
        {
            std::error_code ec;
            if (!temp.path.empty()) fs::remove_all(temp.path, ec);
            if (temp.fd >= 0) ::close(temp.fd);
        }
    };
    // one staging folder per destination folder (rename does not cross file systems)
    std::vector<Staging> staging(paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i) {
        io::remove_stale(folder_of(paths[i]), kStagingMarker, std::string(), io::TempKind::folders);
        try {
            staging[i].temp = io::create_owned_folder(folder_of(paths[i]), "", kStagingMarker);
        } catch (const std::system_error& e) {
            throw std::runtime_error(paths[i].string() + ": cannot make a folder to write it in: " + e.what());
        }
        write(i, staging[i].temp.path / paths[i].filename());
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const fs::path parent = folder_of(paths[i]);
        for (const fs::directory_entry& e : fs::directory_iterator(staging[i].temp.path)) {
            std::error_code ec;
            fs::rename(e.path(), parent / e.path().filename(), ec);
            if (ec) throw std::runtime_error((parent / e.path().filename()).string() + ": cannot move the finished file into place: " + ec.message());
        }
    }
}

}  // namespace echosim::app

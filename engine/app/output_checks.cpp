#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "app/commands.hpp"
#include "io/text_fields.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim::app {
namespace {

// the folder a path names a file in ("." for a bare name)
std::filesystem::path folder_of(const std::filesystem::path& path) { return path.has_parent_path() ? path.parent_path() : "."; }

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
    // a read-only folder (or file system) would fail only at the end, after the work
    if (::access(parent.c_str(), W_OK) != 0) {
        std::fprintf(stderr, "echosim %s: %s %s: cannot write in folder %s: %s\n", command, option, path.c_str(), parent.c_str(),
                     std::generic_category().message(errno).c_str());
        return false;
    }
    return true;
}

bool read_model_option(const char* command, const std::filesystem::path& file, std::optional<tissue::SampleParameters>& tissue)
{
    if (file.empty()) return true;
    try {
        tissue = tissue::read_tissue_model(file).samples;
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
        fs::path folder;
        ~Staging()
        {
            std::error_code ec;
            if (!folder.empty()) fs::remove_all(folder, ec);
        }
    };
    // one staging folder per destination folder (rename does not cross file systems)
    std::vector<Staging> staging(paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i) {
        std::string name = (folder_of(paths[i]) / ".echosim-writing-XXXXXX").string();
        if (!::mkdtemp(name.data()))
            throw std::runtime_error(paths[i].string() + ": cannot make a folder to write it in: " + std::generic_category().message(errno));
        staging[i].folder = name;
        write(i, staging[i].folder / paths[i].filename());
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const fs::path parent = folder_of(paths[i]);
        for (const fs::directory_entry& e : fs::directory_iterator(staging[i].folder)) {
            std::error_code ec;
            fs::rename(e.path(), parent / e.path().filename(), ec);
            if (ec) throw std::runtime_error((parent / e.path().filename()).string() + ": cannot move the finished file into place: " + ec.message());
        }
    }
}

}  // namespace echosim::app

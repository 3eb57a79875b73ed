// Writing a file so that a failure never leaves a broken file looking valid: everything goes to a
// temporary beside FILE (FILE.partial-PID-SIX, io/owned_temp.hpp), which is renamed over FILE only
// once complete and closed; on any failure (or if commit() is never reached) the temporary is
// removed. The temporary is created exclusively and never through a link: a name someone could guess
// and plant a link under (FILE.partial, as it once was) would make every writer overwrite the link's
// target. Temporaries of FILE that a killed process left behind are removed here first (only those
// whose owner is gone). A FILE whose name is as long as the folder allows still gets a temporary:
// the temporary's head is FILE's name cut short. Errors are thrown as `Error` (each file format has
// its own exception type) with the final path in the message. A path that names something other
// than a regular file (a device node, a FIFO, a folder) is refused before anything is written:
// renaming over it would replace the node with a file. A link named as FILE is replaced by the file,
// as rename(2) does; its target is left alone.
#pragma once

#include <cerrno>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

#include <unistd.h>

#include "io/owned_temp.hpp"
#include "io/text_fields.hpp"

namespace echosim::io {

// What a partial file's name adds to (the head of) its file's name: ours alone, so that the sweep of
// stale ones never takes a user's "out.nrrd.partial-2024-drafts" for one.
inline constexpr const char* kPartialMarker = ".echosim-partial-";

// The head of the partial file of a file named `name` in a folder whose names may have `name_max`
// bytes: the name itself, or cut short so that the whole temporary's name fits.
inline std::string partial_head(const std::string& name, std::size_t name_max = NAME_MAX)
{
    const std::size_t added = std::char_traits<char>::length(kPartialMarker) + kOwnedTailMax;
    const std::size_t room = name_max > added + 1 ? name_max - added : 1;
    return name.size() <= room ? name : name.substr(0, room);
}

template <class Error>
class PartialFile {
public:
    explicit PartialFile(const std::filesystem::path& path) : path_(path)
    {
        if (text::is_special_file(path)) fail(std::string(text::not_regular_file) + ": refusing to replace it");
        const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
        const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
        const std::string head = partial_head(path.filename().string(), name_max > 0 ? std::size_t(name_max) : NAME_MAX);
        remove_stale(folder, kPartialMarker, head, TempKind::files);
        OwnedTemp tmp;
        try {
            tmp = create_owned_file(folder, head, kPartialMarker);
        } catch (const std::system_error& e) {
            fail(std::string("cannot write it: ") + e.what());
        }
        tmp_ = tmp.path;
        file_ = ::fdopen(tmp.fd, "wb");  // the FILE owns the descriptor, and with it the lock
        if (!file_) {
            const int e = errno;
            ::close(tmp.fd);
            remove_tmp();
            fail("cannot open " + tmp_.string() + " for writing: " + std::generic_category().message(e));
        }
    }
    PartialFile(const PartialFile&) = delete;
    PartialFile& operator=(const PartialFile&) = delete;
    ~PartialFile()
    {
        if (file_) std::fclose(file_);
        if (!committed_) remove_tmp();
    }

    std::FILE* get() const { return file_; }  // for libraries that write to a FILE*

    void write(const void* data, std::size_t n)
    {
        if (n != 0 && std::fwrite(data, 1, n, file_) != n) fail("write failed: " + std::generic_category().message(errno));
    }
    void write(const std::string& text) { write(text.data(), text.size()); }

    void commit()
    {
        // flushed, then renamed while the descriptor (and with it the lock) is still held: closed
        // first, the lock would be free for a moment in which another writer's sweep could take a
        // temporary whose writer had paused for long for a stale one
        if (std::fflush(file_) != 0) fail("write failed: " + std::generic_category().message(errno));
        std::error_code ec;
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) fail("cannot rename the finished file into place: " + ec.message());
        committed_ = true;
        std::FILE* f = std::exchange(file_, nullptr);
        if (std::fclose(f) != 0) fail("write failed: " + std::generic_category().message(errno));
    }

    [[noreturn]] void fail(const std::string& why) const { text::fail<Error>(path_, why); }

private:
    void remove_tmp() const
    {
        std::error_code ec;
        std::filesystem::remove(tmp_, ec);
    }

    std::filesystem::path path_;
    std::filesystem::path tmp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

// A whole file at once, through PartialFile: the old file stays whole until the new one is.
template <class Error>
void write_file(const std::filesystem::path& path, const std::string& text)
{
    PartialFile<Error> out(path);
    out.write(text);
    out.commit();
}

}  // namespace echosim::io

// Writing a file so that a failure never leaves a broken file looking valid: everything goes to
// FILE.partial, which is renamed over FILE only once complete and closed; on any failure (or if
// commit() is never reached) the partial file is removed. Errors are thrown as `Error` (each file
// format has its own exception type) with the final path in the message. A path that names
// something other than a regular file (a device node, a FIFO, a folder) is refused before anything
// is written: renaming over it would replace the node with a file.
#pragma once

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

#include "io/text_fields.hpp"

namespace echosim::io {

template <class Error>
class PartialFile {
public:
    explicit PartialFile(const std::filesystem::path& path) : path_(path), tmp_(path)
    {
        if (text::is_special_file(path)) fail(std::string(text::not_regular_file) + ": refusing to replace it");
        tmp_ += ".partial";
        file_ = std::fopen(tmp_.c_str(), "wb");
        if (!file_) fail("cannot open " + tmp_.string() + " for writing: " + std::generic_category().message(errno));
    }
    PartialFile(const PartialFile&) = delete;
    PartialFile& operator=(const PartialFile&) = delete;
    ~PartialFile()
    {
        if (file_) std::fclose(file_);
        if (!committed_) {
            std::error_code ec;
            std::filesystem::remove(tmp_, ec);
        }
    }

    std::FILE* get() const { return file_; }  // for libraries that write to a FILE*

    void write(const void* data, std::size_t n)
    {
        if (n != 0 && std::fwrite(data, 1, n, file_) != n) fail("write failed: " + std::generic_category().message(errno));
    }
    void write(const std::string& text) { write(text.data(), text.size()); }

    void commit()
    {
        std::FILE* f = std::exchange(file_, nullptr);
        if (std::fclose(f) != 0) fail("write failed: " + std::generic_category().message(errno));
        std::error_code ec;
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) fail("cannot rename the finished file into place: " + ec.message());
        committed_ = true;
    }

    [[noreturn]] void fail(const std::string& why) const { text::fail<Error>(path_, why); }

private:
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

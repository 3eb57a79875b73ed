#include "io/owned_temp.hpp"

#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <random>
#include <system_error>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace echosim::io {
namespace {

constexpr std::size_t kRandomChars = 6;

std::string random_chars()
{
    static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    std::random_device device;
    std::uniform_int_distribution<std::size_t> pick(0, sizeof alphabet - 2);
    std::string s(kRandomChars, ' ');
    for (char& c : s) c = alphabet[pick(device)];
    return s;
}

std::string owned_name(const std::string& head, const std::string& marker, const std::string& six)
{
    return head + marker + std::to_string(::getpid()) + "-" + six;
}

[[noreturn]] void throw_errno(const std::filesystem::path& path, const char* what)
{
    throw std::system_error(errno, std::generic_category(), path.string() + ": " + what);
}

// The PID in a temporary's name (after HEAD MARKER), or 0 when it is not one.
pid_t owned_pid(const std::string& name, const std::string& marker, std::string* head)
{
    // ... MARKER digits "-" SIX
    if (name.size() < marker.size() + 2 + kRandomChars) return 0;
    const std::size_t dash = name.size() - kRandomChars - 1;
    if (name[dash] != '-') return 0;
    // the six are mkdtemp's or random_chars': letters and digits (a user's "out.nrrd.partial-2024-drafts" is not ours)
    for (std::size_t i = dash + 1; i < name.size(); ++i)
        if (!std::isalnum(static_cast<unsigned char>(name[i]))) return 0;
    std::size_t digits = dash;
    while (digits > 0 && name[digits - 1] >= '0' && name[digits - 1] <= '9') --digits;
    if (digits == dash || dash - digits > 10 || digits < marker.size()) return 0;
    if (name.compare(digits - marker.size(), marker.size(), marker) != 0) return 0;
    const long long pid = std::atoll(name.substr(digits, dash - digits).c_str());
    if (pid <= 0 || pid > 0x7fffffff) return 0;
    if (head) *head = name.substr(0, digits - marker.size());
    return pid_t(pid);
}

bool process_alive(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

// Whether the temporary at `path` (not a link: checked by the caller) belongs to no live process.
bool owner_gone(const std::filesystem::path& path, pid_t pid, const struct stat& st)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return false;
    const int locked = ::flock(fd, LOCK_EX | LOCK_NB);
    const int lock_errno = errno;
    ::close(fd);  // releases the lock taken just now; the owner's is its own
    if (locked != 0 && lock_errno == EWOULDBLOCK) return false;  // its owner holds it
    const bool old = std::chrono::system_clock::now() - std::chrono::system_clock::from_time_t(st.st_mtime) > kStaleAge;
    if (locked != 0) return old && !process_alive(pid);  // the lock cannot be tested here
    return old || !process_alive(pid);
}

}  // namespace

OwnedTemp create_owned_file(const std::filesystem::path& folder, const std::string& head, const std::string& marker)
{
    for (int attempt = 0;; ++attempt) {
        OwnedTemp t{folder / owned_name(head, marker, random_chars())};
        // O_EXCL and O_NOFOLLOW: never a file or link that was there, whoever put it there
        t.fd = ::open(t.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (t.fd < 0) {
            if (errno == EEXIST && attempt < 100) continue;
            throw_errno(t.path, "cannot create a temporary file");
        }
        if (::flock(t.fd, LOCK_EX) != 0 && errno != EOPNOTSUPP && errno != ENOLCK && errno != EBADF) {
            const int e = errno;
            ::close(t.fd);
            ::unlink(t.path.c_str());
            errno = e;
            throw_errno(t.path, "cannot lock a temporary file");
        }
        return t;
    }
}

OwnedTemp create_owned_folder(const std::filesystem::path& folder, const std::string& head, const std::string& marker)
{
    std::string name = (folder / owned_name(head, marker, "XXXXXX")).string();
    if (!::mkdtemp(name.data())) throw_errno(name, "cannot create a temporary folder");
    OwnedTemp t{name};
    t.fd = ::open(name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (t.fd < 0 || (::flock(t.fd, LOCK_EX) != 0 && errno != EOPNOTSUPP && errno != ENOLCK && errno != EBADF)) {
        const int e = errno;
        if (t.fd >= 0) ::close(t.fd);
        ::rmdir(name.c_str());
        errno = e;
        throw_errno(name, "cannot lock a temporary folder");
    }
    return t;
}

std::optional<std::string> owned_head(const std::string& name, const std::string& marker)
{
    std::string head;
    if (owned_pid(name, marker, &head) == 0) return std::nullopt;
    return head;
}

std::size_t remove_stale(const std::filesystem::path& folder, const std::string& marker, const std::optional<std::string>& head,
                         TempKind kind)
{
    std::size_t removed = 0;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::string h;
        const pid_t pid = owned_pid(name, marker, &h);
        if (pid == 0 || (head && h != *head)) continue;
        struct stat st {};
        if (::lstat(it->path().c_str(), &st) != 0 || st.st_uid != ::geteuid()) continue;  // never a link, nor another user's
        const bool file = S_ISREG(st.st_mode), dir = S_ISDIR(st.st_mode);
        if (!(kind == TempKind::files ? file : kind == TempKind::folders ? dir : file || dir)) continue;
        if (!owner_gone(it->path(), pid, st)) continue;
        std::error_code remove_ec;
        if (std::filesystem::remove_all(it->path(), remove_ec) > 0 && !remove_ec) ++removed;
    }
    return removed;
}

}  // namespace echosim::io

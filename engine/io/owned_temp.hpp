// Temporary files and folders that say who owns them, so that one left behind by a process that
// was killed (SIGKILL, a power cut) can be told from one another process is still writing, and
// removed by the next run that writes there.
//
// A temporary is named HEAD MARKER PID "-" SIX, e.g. "v.nrrd.partial-4711-a8Zq0c": PID is the
// process that made it, SIX random letters and digits make the name unique. It is created
// exclusively (O_CREAT | O_EXCL | O_NOFOLLOW, or mkdtemp), never by following a link that someone
// planted under a name they could guess, and its owner holds an exclusive flock(2) on it while it
// lives. Its owner is gone when that lock is free and either PID is not a live process or the
// temporary is older than kStaleAge (the PID reused by another program, or one from another PID
// namespace); the lock alone would do, but a temporary is locked a moment after it is made, and the
// PID covers that moment. On a file system whose flock cannot be tested (some NFS set-ups), the lock
// counts as free only once the temporary is older than kStaleAge and its PID is gone.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

namespace echosim::io {

// Older than this, a temporary whose lock is free is stale even if its PID is alive again.
inline constexpr std::chrono::minutes kStaleAge{10};

// The longest MARKER-less tail a temporary's name adds: "PID-SIX" (a PID has at most 10 digits).
inline constexpr std::size_t kOwnedTailMax = 10 + 1 + 6;

// An open temporary: its path and the descriptor that holds its lock (close it to release).
struct OwnedTemp {
    std::filesystem::path path;
    int fd = -1;
};

// A new empty file `folder / (head + marker + PID-SIX)`, opened for writing (mode 0666 less the
// umask, as a plain fopen would make it) and locked. Throws std::system_error naming the path.
OwnedTemp create_owned_file(const std::filesystem::path& folder, const std::string& head, const std::string& marker);

// A new empty folder `folder / (head + marker + PID-SIX)` (mode 0700), opened and locked.
// Throws std::system_error naming the path.
OwnedTemp create_owned_folder(const std::filesystem::path& folder, const std::string& head, const std::string& marker);

// The HEAD of `name` when it is a temporary's name with this marker (HEAD MARKER PID "-" SIX).
std::optional<std::string> owned_head(const std::string& name, const std::string& marker);

// What a sweep of stale temporaries may remove: the kind its writer makes, nothing else.
enum class TempKind { files, folders, both };

// Removes, from `folder`, the temporaries with this marker (and exactly this head, when one is
// given: "" is the empty head) whose owner is gone: of `kind`, owned by this user, named exactly as
// create_owned_* names them (six letters or digits last), never a link or anything else. Errors are
// ignored (a stale temporary is clutter, not a failure); returns how many were removed.
std::size_t remove_stale(const std::filesystem::path& folder, const std::string& marker, const std::optional<std::string>& head = {},
                         TempKind kind = TempKind::both);

}  // namespace echosim::io

// The trainee records (DESIGN.md §3, "trainee records"): every exam, from the window or headless,
// stored in an SQLite database (the user's data folder by default; `--records PATH` for another)
// with its trainee, case, protocol, per-station results, flagged errors, score and time. The
// learning curve (exam/learning_curve.hpp) and the xAPI export (exam/xapi.hpp) read it.
//
// Crash safety: the database runs in WAL mode with synchronous=FULL, and each exam is stored in one
// transaction (BEGIN IMMEDIATE ... COMMIT), so a process killed mid-store leaves the exams stored
// before it whole and no part of the one it was storing (tests/exam/records_test.cpp kills one).
// The schema has a version (PRAGMA user_version) and the file an application id: a file of a newer
// schema, or an SQLite file of another program, is refused with a message naming it, never changed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "exam/exam_report.hpp"

struct sqlite3;

namespace echosim::exam {

// What went wrong with a records database; the message opens with the file.
struct RecordsError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct SessionRecord {
    std::int64_t id = 0;  // in the order stored
    std::string trainee;
    std::string case_id, case_title, protocol;
    std::string started_utc;  // the report's: "" from a repeatable (scripted) run
    std::string stored_utc;   // when it was stored, ISO 8601 UTC
    double score = 0, pass_mark = 0;
    bool passed = false;
    double duration_s = 0, path_mm = 0;
    std::string conclusion;
    bool dvt_present = false;
};

struct StationRecord {
    std::int64_t session_id = 0;
    int position = 0;  // in the protocol's order, from 0
    std::string name, segment;
    double s_cm = 0;
    bool reached = false;
    double collapse_ratio = 0, peak_force_N = 0;  // NaN where the report had no finite value
    bool adequate = false;  // reached and pressed hard enough (exam/station_status.hpp)
    bool thrombosed = false;
    std::string call;       // call_name()
    bool correct = false;   // the call right
    bool success() const { return adequate && correct; }  // the learning curve's success
};

struct ErrorRecord {
    std::int64_t session_id = 0;
    int position = 0;
    std::string kind, station;  // error_name(); the station's name or ""
    double time_s = 0;
    std::string detail;
};

// A callback inside the store's transaction after each row is written (table, row within the
// table): for tests that kill the process there. Never needed otherwise.
using StoreHook = std::function<void(const char* table, std::size_t row)>;

struct RecordsOptions {
    bool create = true;          // false: a missing file is an error (listing must not make one)
    int busy_timeout_ms = 5000;  // how long to wait for another process's write before "locked"
};

// One open database. Use it from one thread at a time (the connection is opened without SQLite's
// own mutex); several processes may each hold one: SQLite's locks order their writes.
class Records {
public:
    static constexpr int kSchemaVersion = 1;
    static constexpr std::int32_t kApplicationId = 0x45434853;  // "ECHS", in the file's header

    // Opens the database, making it (and its folder) when missing and options.create. Throws
    // RecordsError naming the file: cannot be opened or made, not an SQLite database, another
    // program's database, a newer schema, locked beyond the timeout.
    explicit Records(const std::filesystem::path& file, const RecordsOptions& options = {});
    ~Records();
    Records(Records&& other) noexcept;
    Records& operator=(Records&& other) noexcept;
    Records(const Records&) = delete;
    Records& operator=(const Records&) = delete;

    const std::filesystem::path& path() const { return path_; }
    // a random UUID given to the database when it was made: statement ids derive from it, so two
    // databases' sessions numbered alike never share an id in a learning record store
    const std::string& database_id() const { return database_id_; }

    // Stores the exam in one transaction; its session's id.
    std::int64_t store(const ExamReport& report, const StoreHook& hook = {});

    // The sessions in the order stored, of one trainee or of all.
    std::vector<SessionRecord> sessions(const std::optional<std::string>& trainee = std::nullopt) const;
    std::vector<StationRecord> stations(std::int64_t session_id) const;
    std::vector<ErrorRecord> errors(std::int64_t session_id) const;
    std::vector<std::string> trainees() const;  // by name

    // SQLite's PRAGMA integrity_check: "ok", or what it found.
    std::string integrity_check() const;

private:
    [[noreturn]] void fail(const std::string& what, int code) const;
    void exec(const char* sql) const;
    void open_schema();

    std::filesystem::path path_;
    sqlite3* db_ = nullptr;
    std::string database_id_;
    int busy_timeout_ms_ = 0;
};

// What `echosim exam` and the window call once an exam is scored.
std::int64_t store_exam(Records& records, const ExamReport& report);

// The default database: $XDG_DATA_HOME/echosim/records.sqlite when XDG_DATA_HOME is set to an
// absolute path (the XDG base directory rules ignore a relative one), else
// $HOME/.local/share/echosim/records.sqlite. Throws RecordsError when neither is usable.
std::filesystem::path default_records_path(const char* xdg_data_home, const char* home);
std::filesystem::path default_records_path();  // from the environment

}  // namespace echosim::exam

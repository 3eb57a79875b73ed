#include "exam/records.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <system_error>
#include <utility>

#include <sqlite3.h>

#include "exam/report_text.hpp"
#include "exam/station_status.hpp"
#include "exam/uuid.hpp"

namespace echosim::exam {
namespace {

// Schema version 1. Reals may be NULL: SQLite stores a NaN as NULL, read back as NaN.
constexpr const char* kSchemaV1 = R"(
CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL) WITHOUT ROWID;
CREATE TABLE trainees (id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE);
CREATE TABLE sessions (
  id INTEGER PRIMARY KEY,
  trainee_id INTEGER NOT NULL REFERENCES trainees(id),
  case_id TEXT NOT NULL, case_title TEXT NOT NULL, protocol TEXT NOT NULL,
  started_utc TEXT NOT NULL, stored_utc TEXT NOT NULL,
  score REAL, pass_mark REAL, passed INTEGER NOT NULL,
  duration_s REAL, path_mm REAL, conclusion TEXT NOT NULL, dvt_present INTEGER NOT NULL);
CREATE INDEX sessions_by_trainee ON sessions (trainee_id, id);
CREATE TABLE station_results (
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  position INTEGER NOT NULL,
  name TEXT NOT NULL, segment TEXT NOT NULL, s_cm REAL,
  reached INTEGER NOT NULL, collapse_ratio REAL, peak_force_N REAL,
  adequate INTEGER NOT NULL, thrombosed INTEGER NOT NULL, call TEXT NOT NULL, correct INTEGER NOT NULL,
  PRIMARY KEY (session_id, position)) WITHOUT ROWID;
CREATE TABLE errors (
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  position INTEGER NOT NULL,
  kind TEXT NOT NULL, station TEXT NOT NULL, time_s REAL, detail TEXT NOT NULL,
  PRIMARY KEY (session_id, position)) WITHOUT ROWID;
)";

std::string utc_now()
{
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

// One prepared statement, finalised when it goes; its failures reported through the owner.
class Statement {
public:
    Statement(sqlite3* db, const char* sql, const std::function<void(const std::string&, int)>& fail) : db_(db), fail_(fail)
    {
        const int rc = sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr);
        if (rc != SQLITE_OK) fail_(sqlite3_errmsg(db), rc);
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    Statement& bind(int i, const std::string& v)
    {
        check(sqlite3_bind_text(stmt_, i, v.data(), int(v.size()), SQLITE_TRANSIENT));
        return *this;
    }
    Statement& bind(int i, std::int64_t v)
    {
        check(sqlite3_bind_int64(stmt_, i, v));
        return *this;
    }
    Statement& bind(int i, int v) { return bind(i, std::int64_t(v)); }
    Statement& bind(int i, bool v) { return bind(i, std::int64_t(v ? 1 : 0)); }
    Statement& bind(int i, double v)
    {
        check(std::isfinite(v) ? sqlite3_bind_double(stmt_, i, v) : sqlite3_bind_null(stmt_, i));
        return *this;
    }

    // true while there is a row
    bool step()
    {
        const int rc = sqlite3_step(stmt_);
        if (rc == SQLITE_ROW) return true;
        if (rc != SQLITE_DONE) fail_(sqlite3_errmsg(db_), rc);
        return false;
    }
    void run()
    {
        while (step()) {
        }
    }
    // ready to run again with new values
    void reset()
    {
        sqlite3_reset(stmt_);
        sqlite3_clear_bindings(stmt_);
    }

    std::int64_t integer(int col) const { return sqlite3_column_int64(stmt_, col); }
    double real(int col) const
    {
        return sqlite3_column_type(stmt_, col) == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN() : sqlite3_column_double(stmt_, col);
    }
    std::string text(int col) const
    {
        const auto* p = sqlite3_column_text(stmt_, col);
        return p ? std::string(reinterpret_cast<const char*>(p), std::size_t(sqlite3_column_bytes(stmt_, col))) : std::string();
    }

private:
    void check(int rc)
    {
        if (rc != SQLITE_OK) fail_(sqlite3_errmsg(db_), rc);
    }
    sqlite3* db_;
    sqlite3_stmt* stmt_ = nullptr;
    std::function<void(const std::string&, int)> fail_;
};

}  // namespace

void Records::fail(const std::string& what, int code) const
{
    std::string why;
    switch (code & 0xFF) {  // the primary code of an extended one
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
        why = "the records database is locked by another process (waited " + std::to_string(busy_timeout_ms_) + " ms): " + what;
        break;
    case SQLITE_NOTADB: why = "not an SQLite database (" + what + "): not a records file"; break;
    case SQLITE_CORRUPT: why = "the records database is damaged (" + what + ")"; break;
    case SQLITE_READONLY: why = "cannot write the records database: " + what; break;
    case SQLITE_CANTOPEN: why = "cannot open the records database: " + what; break;
    case SQLITE_FULL: why = "the disk is full: " + what; break;
    default: why = what;
    }
    throw RecordsError(path_.string() + ": " + why);
}

void Records::exec(const char* sql) const
{
    char* message = nullptr;
    const int rc = sqlite3_exec(db_, sql, nullptr, nullptr, &message);
    if (rc != SQLITE_OK) {
        const std::string what = message ? message : sqlite3_errmsg(db_);
        sqlite3_free(message);
        fail(what, rc);
    }
}

Records::Records(const std::filesystem::path& file, const RecordsOptions& options) : path_(file), busy_timeout_ms_(options.busy_timeout_ms)
{
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    const bool exists = !ec && std::filesystem::exists(status);
    if (exists && !std::filesystem::is_regular_file(status))
        throw RecordsError(file.string() + ": not a regular file (a folder, a device or a FIFO): not a records database");
    if (!exists) {
        if (!options.create) throw RecordsError(file.string() + ": no records database there (no exam stored in it yet)");
        if (file.has_parent_path()) {
            std::filesystem::create_directories(file.parent_path(), ec);
            if (ec) throw RecordsError(file.string() + ": cannot make its folder: " + ec.message());
        }
    }
    const int flags = SQLITE_OPEN_READWRITE | (options.create ? SQLITE_OPEN_CREATE : 0) | SQLITE_OPEN_NOMUTEX;
    const int rc = sqlite3_open_v2(file.c_str(), &db_, flags, nullptr);
    if (rc != SQLITE_OK) {
        const std::string what = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
        sqlite3_close(db_);
        db_ = nullptr;
        fail(what, rc);
    }
    try {
        sqlite3_extended_result_codes(db_, 1);
        sqlite3_busy_timeout(db_, options.busy_timeout_ms);
        open_schema();
    } catch (...) {
        sqlite3_close(db_);
        db_ = nullptr;
        throw;
    }
}

void Records::open_schema()
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    const auto pragma_int = [&](const char* sql) {
        Statement st(db_, sql, failer);
        return st.step() ? st.integer(0) : 0;
    };
    // the header's fields first: reading them is where a file that is not SQLite shows it
    std::int64_t app = pragma_int("PRAGMA application_id");
    std::int64_t version = pragma_int("PRAGMA user_version");
    if (app != 0 && app != kApplicationId)
        throw RecordsError(path_.string() + ": an SQLite database of another program (application id " + std::to_string(app) +
                           "), not echosim's records: refusing to change it");
    if (version > kSchemaVersion)
        throw RecordsError(path_.string() + ": records of schema version " + std::to_string(version) + ", newer than this echosim's (" +
                           std::to_string(kSchemaVersion) + "): written by a newer echosim; use that one (this one will not change the file)");

    if (app == 0) {
        // a new file: made in one transaction, its header fields last, so a crash leaves either
        // nothing or the whole schema; BEGIN IMMEDIATE so two processes making it at once take turns.
        // Nothing is written before the check for another program's tables (WAL mode comes after:
        // setting it writes the header)
        exec("BEGIN IMMEDIATE");
        try {
            app = pragma_int("PRAGMA application_id");  // again, now that no other writer can be at it
            if (app == 0) {
                if (pragma_int("SELECT count(*) FROM sqlite_schema") != 0)
                    throw RecordsError(path_.string() + ": an SQLite database of another program (it has tables but no echosim " +
                                       "application id): refusing to change it");
                exec(kSchemaV1);
                Statement meta(db_, "INSERT INTO meta (key, value) VALUES ('database_id', ?1)", failer);
                meta.bind(1, uuid_text(uuid_v4_random())).run();
                exec(("PRAGMA application_id = " + std::to_string(kApplicationId)).c_str());
                exec(("PRAGMA user_version = " + std::to_string(kSchemaVersion)).c_str());
            }
            exec("COMMIT");
        } catch (...) {
            sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
            throw;
        }
        version = pragma_int("PRAGMA user_version");
    }
    if (version != kSchemaVersion)  // a schema older than ours: there is none yet to migrate from
        throw RecordsError(path_.string() + ": records of schema version " + std::to_string(version) + ", which this echosim cannot read");

    // WAL: a crash mid-write leaves the committed exams whole; FULL: a committed exam survives a
    // power cut too (an exam is a few rows; the fsync costs nothing a trainee notices)
    exec("PRAGMA journal_mode=WAL");
    exec("PRAGMA synchronous=FULL");
    exec("PRAGMA foreign_keys=ON");
    Statement id(db_, "SELECT value FROM meta WHERE key = 'database_id'", failer);
    if (!id.step() || !parse_uuid(id.text(0))) throw RecordsError(path_.string() + ": the records database has no valid database_id in its meta table");
    database_id_ = id.text(0);
}

Records::~Records()
{
    if (db_) sqlite3_close(db_);
}

Records::Records(Records&& other) noexcept
    : path_(std::move(other.path_)), db_(std::exchange(other.db_, nullptr)), database_id_(std::move(other.database_id_)),
      busy_timeout_ms_(other.busy_timeout_ms_)
{
}

Records& Records::operator=(Records&& other) noexcept
{
    if (this != &other) {
        if (db_) sqlite3_close(db_);
        path_ = std::move(other.path_);
        db_ = std::exchange(other.db_, nullptr);
        database_id_ = std::move(other.database_id_);
        busy_timeout_ms_ = other.busy_timeout_ms_;
    }
    return *this;
}

std::int64_t Records::store(const ExamReport& r, const StoreHook& hook)
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    // IMMEDIATE: the write lock is taken here, so another writer makes this wait (and then fail
    // naming the file) before anything is written, not halfway
    exec("BEGIN IMMEDIATE");
    try {
        const std::string trainee = valid_utf8(r.trainee);
        Statement(db_, "INSERT OR IGNORE INTO trainees (name) VALUES (?1)", failer).bind(1, trainee).run();
        Statement who(db_, "SELECT id FROM trainees WHERE name = ?1", failer);
        who.bind(1, trainee);
        if (!who.step()) fail("the trainee just stored is not there", SQLITE_INTERNAL);
        const std::int64_t trainee_id = who.integer(0);
        if (hook) hook("trainees", 0);

        Statement session(db_,
                          "INSERT INTO sessions (trainee_id, case_id, case_title, protocol, started_utc, stored_utc, score, pass_mark, "
                          "passed, duration_s, path_mm, conclusion, dvt_present) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13)",
                          failer);
        session.bind(1, trainee_id).bind(2, valid_utf8(r.case_id)).bind(3, valid_utf8(r.case_title)).bind(4, valid_utf8(r.protocol));
        session.bind(5, valid_utf8(r.started_utc)).bind(6, utc_now()).bind(7, r.score).bind(8, r.pass_mark).bind(9, r.passed);
        session.bind(10, r.motion.duration_s).bind(11, r.motion.path_mm).bind(12, valid_utf8(r.conclusion)).bind(13, r.dvt_present);
        session.run();
        const std::int64_t id = sqlite3_last_insert_rowid(db_);
        if (hook) hook("sessions", 0);

        Statement station(db_,
                          "INSERT INTO station_results (session_id, position, name, segment, s_cm, reached, collapse_ratio, peak_force_N, "
                          "adequate, thrombosed, call, correct) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)",
                          failer);
        for (std::size_t i = 0; i < r.stations.size(); ++i) {
            const StationResult& s = r.stations[i];
            station.bind(1, id).bind(2, std::int64_t(i)).bind(3, valid_utf8(s.name)).bind(4, valid_utf8(s.segment)).bind(5, s.s_cm);
            station.bind(6, s.reached).bind(7, s.collapse_ratio).bind(8, s.peak_force_N).bind(9, adequately_pressed(r, i));
            station.bind(10, s.thrombosed).bind(11, std::string(call_name(s.call))).bind(12, s.call_correct);
            station.run();
            station.reset();
            if (hook) hook("station_results", i);
        }
        Statement error(db_, "INSERT INTO errors (session_id, position, kind, station, time_s, detail) VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
                        failer);
        for (std::size_t i = 0; i < r.errors.size(); ++i) {
            const FlaggedError& e = r.errors[i];
            error.bind(1, id).bind(2, std::int64_t(i)).bind(3, std::string(error_name(e.kind))).bind(4, valid_utf8(e.station));
            error.bind(5, e.time_s).bind(6, valid_utf8(e.detail));
            error.run();
            error.reset();
            if (hook) hook("errors", i);
        }
        exec("COMMIT");
        return id;
    } catch (...) {
        sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
        throw;
    }
}

std::vector<SessionRecord> Records::sessions(const std::optional<std::string>& trainee) const
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    Statement st(db_,
                 "SELECT s.id, t.name, s.case_id, s.case_title, s.protocol, s.started_utc, s.stored_utc, s.score, s.pass_mark, s.passed, "
                 "s.duration_s, s.path_mm, s.conclusion, s.dvt_present FROM sessions s JOIN trainees t ON t.id = s.trainee_id "
                 "WHERE ?1 IS NULL OR t.name = ?1 ORDER BY s.id",
                 failer);
    if (trainee) st.bind(1, valid_utf8(*trainee));
    std::vector<SessionRecord> out;
    while (st.step()) {
        SessionRecord s;
        s.id = st.integer(0);
        s.trainee = st.text(1);
        s.case_id = st.text(2);
        s.case_title = st.text(3);
        s.protocol = st.text(4);
        s.started_utc = st.text(5);
        s.stored_utc = st.text(6);
        s.score = st.real(7);
        s.pass_mark = st.real(8);
        s.passed = st.integer(9) != 0;
        s.duration_s = st.real(10);
        s.path_mm = st.real(11);
        s.conclusion = st.text(12);
        s.dvt_present = st.integer(13) != 0;
        out.push_back(std::move(s));
    }
    return out;
}

std::vector<StationRecord> Records::stations(std::int64_t session_id) const
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    Statement st(db_,
                 "SELECT position, name, segment, s_cm, reached, collapse_ratio, peak_force_N, adequate, thrombosed, call, correct "
                 "FROM station_results WHERE session_id = ?1 ORDER BY position",
                 failer);
    st.bind(1, session_id);
    std::vector<StationRecord> out;
    while (st.step()) {
        StationRecord s;
        s.session_id = session_id;
        s.position = int(st.integer(0));
        s.name = st.text(1);
        s.segment = st.text(2);
        s.s_cm = st.real(3);
        s.reached = st.integer(4) != 0;
        s.collapse_ratio = st.real(5);
        s.peak_force_N = st.real(6);
        s.adequate = st.integer(7) != 0;
        s.thrombosed = st.integer(8) != 0;
        s.call = st.text(9);
        s.correct = st.integer(10) != 0;
        out.push_back(std::move(s));
    }
    return out;
}

std::vector<ErrorRecord> Records::errors(std::int64_t session_id) const
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    Statement st(db_, "SELECT position, kind, station, time_s, detail FROM errors WHERE session_id = ?1 ORDER BY position", failer);
    st.bind(1, session_id);
    std::vector<ErrorRecord> out;
    while (st.step()) {
        ErrorRecord e;
        e.session_id = session_id;
        e.position = int(st.integer(0));
        e.kind = st.text(1);
        e.station = st.text(2);
        e.time_s = st.real(3);
        e.detail = st.text(4);
        out.push_back(std::move(e));
    }
    return out;
}

std::vector<std::string> Records::trainees() const
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    Statement st(db_, "SELECT name FROM trainees ORDER BY name", failer);
    std::vector<std::string> out;
    while (st.step()) out.push_back(st.text(0));
    return out;
}

std::string Records::integrity_check() const
{
    const auto failer = [this](const std::string& what, int rc) { fail(what, rc); };
    Statement st(db_, "PRAGMA integrity_check", failer);
    std::string out;
    while (st.step()) out += (out.empty() ? "" : "\n") + st.text(0);
    return out;
}

std::int64_t store_exam(Records& records, const ExamReport& report) { return records.store(report); }

std::filesystem::path default_records_path(const char* xdg_data_home, const char* home)
{
    const std::filesystem::path leaf = std::filesystem::path("echosim") / "records.sqlite";
    if (xdg_data_home && *xdg_data_home && std::filesystem::path(xdg_data_home).is_absolute()) return xdg_data_home / leaf;
    if (home && *home) return std::filesystem::path(home) / ".local" / "share" / leaf;
    throw RecordsError("no folder for the records: neither XDG_DATA_HOME (absolute) nor HOME is set; give one with --records PATH");
}

std::filesystem::path default_records_path() { return default_records_path(std::getenv("XDG_DATA_HOME"), std::getenv("HOME")); }

}  // namespace echosim::exam

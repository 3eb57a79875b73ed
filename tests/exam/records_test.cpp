// The trainee records: exams stored and read back, the refusals (a newer schema, another program's
// database, not a database, locked, a bad path) naming the file, and a process killed with SIGKILL
// in the middle of storing an exam leaving the database intact without that exam.
#include <cmath>
#include <csignal>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include "exam/records.hpp"
#include "report_fixture.hpp"
#include "test_files.hpp"

namespace echosim::exam {
namespace {

using echosim::test::expect_error_naming;
using echosim::test::read_bytes;
using echosim::test::temp_path;
using test::make_report;

std::filesystem::path fresh_db(const std::string& name)
{
    const auto dir = temp_path("records", name);
    std::filesystem::remove_all(dir);
    return dir / "records.sqlite";
}

void raw_sql(const std::filesystem::path& file, const char* sql)
{
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
    char* message = nullptr;
    EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, &message), SQLITE_OK) << (message ? message : "");
    sqlite3_free(message);
    sqlite3_close(db);
}

TEST(Records, ExamsStoredReadBackInOrder)
{
    const auto file = fresh_db("round_trip");
    ExamReport a = make_report(), b = make_report(), c = make_report();
    b.score = 0.9;
    b.passed = true;
    b.case_id = "healthy";
    b.stations[1].peak_force_N = std::nan("");  // a value the scorer could not give is kept as unknown
    c.trainee = "Grace Hopper";
    std::string db_id;
    {
        Records records(file);  // made with its folder
        db_id = records.database_id();
        EXPECT_EQ(store_exam(records, a), 1);
        EXPECT_EQ(store_exam(records, b), 2);
        EXPECT_EQ(store_exam(records, c), 3);
        EXPECT_EQ(records.integrity_check(), "ok");
    }
    const Records records(file, {.create = false});
    EXPECT_EQ(records.database_id(), db_id);
    EXPECT_EQ(records.trainees(), (std::vector<std::string>{"Ada Lovelace", "Grace Hopper"}));
    EXPECT_EQ(records.sessions().size(), 3u);
    const auto ada = records.sessions("Ada Lovelace");
    ASSERT_EQ(ada.size(), 2u);
    EXPECT_EQ(ada[0].id, 1);
    EXPECT_EQ(ada[0].case_id, "fv-isolated-acute");
    EXPECT_EQ(ada[0].case_title, a.case_title);
    EXPECT_EQ(ada[0].protocol, "extended");
    EXPECT_EQ(ada[0].started_utc, "");
    EXPECT_EQ(ada[0].stored_utc.size(), 20u);  // 2026-11-27T09:00:00Z
    EXPECT_DOUBLE_EQ(ada[0].score, 0.625);
    EXPECT_FALSE(ada[0].passed);
    EXPECT_DOUBLE_EQ(ada[0].duration_s, 16.0);
    EXPECT_DOUBLE_EQ(ada[0].path_mm, 312.5);
    EXPECT_TRUE(ada[0].dvt_present);
    EXPECT_EQ(ada[1].id, 2);
    EXPECT_EQ(ada[1].case_id, "healthy");
    EXPECT_TRUE(ada[1].passed);

    const auto st = records.stations(1);
    ASSERT_EQ(st.size(), 4u);
    EXPECT_EQ(st[0].name, "CFV");
    EXPECT_EQ(st[0].segment, "cfv");
    EXPECT_DOUBLE_EQ(st[0].s_cm, 1.0);
    EXPECT_TRUE(st[0].reached);
    EXPECT_DOUBLE_EQ(st[0].collapse_ratio, 0.02225);
    EXPECT_DOUBLE_EQ(st[0].peak_force_N, 14.25);
    EXPECT_TRUE(st[0].adequate);
    EXPECT_EQ(st[0].call, "compressible");
    EXPECT_TRUE(st[0].success());
    EXPECT_FALSE(st[1].adequate);  // too little pressure flagged there
    EXPECT_FALSE(st[1].correct);
    EXPECT_FALSE(st[2].reached);
    EXPECT_EQ(st[2].call, "none");
    EXPECT_TRUE(st[3].thrombosed);
    EXPECT_TRUE(st[3].success());
    EXPECT_TRUE(std::isnan(records.stations(2)[1].peak_force_N));

    const auto errors = records.errors(1);
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_EQ(errors[0].kind, "too-little-pressure");
    EXPECT_EQ(errors[0].station, "SFJ");
    EXPECT_DOUBLE_EQ(errors[0].time_s, 9.0);
    EXPECT_EQ(errors[2].detail, "never reached");
    std::filesystem::remove_all(file.parent_path());
}

TEST(Records, ANewerSchemaIsRefusedAndLeftAlone)
{
    const auto file = fresh_db("newer");
    { Records records(file); }
    raw_sql(file, "PRAGMA user_version = 7");
    const std::string before = read_bytes(file);
    expect_error_naming<RecordsError>(file, {"schema version 7", "newer"}, [&] { Records again(file); });
    EXPECT_TRUE(read_bytes(file) == before) << "the file was changed";
    std::filesystem::remove_all(file.parent_path());
}

TEST(Records, AnotherProgramsDatabaseIsRefusedAndLeftAlone)
{
    const auto file = fresh_db("other");
    std::filesystem::create_directories(file.parent_path());
    raw_sql(file, "CREATE TABLE photos (id INTEGER PRIMARY KEY, name TEXT)");
    const std::string before = read_bytes(file);
    expect_error_naming<RecordsError>(file, {"another program"}, [&] { Records records(file); });
    EXPECT_TRUE(read_bytes(file) == before) << "the file was changed";
    raw_sql(file, "PRAGMA application_id = 1234");
    expect_error_naming<RecordsError>(file, {"another program", "1234"}, [&] { Records records(file); });
    std::filesystem::remove_all(file.parent_path());
}

TEST(Records, NotADatabaseMissingOrABadPathIsNamed)
{
    const auto file = fresh_db("not_db");
    std::filesystem::create_directories(file.parent_path());
    echosim::test::write_bytes(file, std::string(4096, 'x'));
    expect_error_naming<RecordsError>(file, {"not an SQLite database"}, [&] { Records records(file); });
    const auto missing = file.parent_path() / "missing.sqlite";
    expect_error_naming<RecordsError>(missing, {"no records database"}, [&] { Records records(missing, {.create = false}); });
    EXPECT_FALSE(std::filesystem::exists(missing));
    const auto under_file = file / "records.sqlite";  // its "folder" is a regular file
    expect_error_naming<RecordsError>(under_file, {"cannot"}, [&] { Records records(under_file); });
    expect_error_naming<RecordsError>(file.parent_path(), {"not a regular file"}, [&] { Records records(file.parent_path()); });
    std::filesystem::remove_all(file.parent_path());
}

TEST(Records, ALockedDatabaseIsNamedAfterTheTimeout)
{
    const auto file = fresh_db("locked");
    Records records(file, {.create = true, .busy_timeout_ms = 50});
    sqlite3* other = nullptr;
    ASSERT_EQ(sqlite3_open(file.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
    expect_error_naming<RecordsError>(file, {"locked by another process"}, [&] { records.store(make_report()); });
    sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(other);
    EXPECT_EQ(records.store(make_report()), 1);  // and works once the other is done
    std::filesystem::remove_all(file.parent_path());
}

// A child stores two exams, then begins a third large enough that SQLite has spilled its
// uncommitted pages into the write-ahead log, and is killed with SIGKILL there. The parent then
// finds the database intact, the two exams whole and no trace of the third.
TEST(Records, ACrashMidWriteLeavesTheDatabaseIntact)
{
    const auto file = fresh_db("crash");
    { Records records(file); }  // made by the parent: the child only writes
    ExamReport big = make_report();
    big.trainee = "Killed Midway";
    for (int i = 0; i < 6000; ++i)  // ~12 MB of rows: beyond SQLite's page cache (2 MB)
        big.errors.push_back({ErrorKind::oblique_plane, "CFV", double(i), std::string(2000, char('a' + i % 26))});

    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::close(ready[0]);
        try {
            Records records(file);
            records.store(make_report());
            ExamReport second = make_report();
            second.case_id = "healthy";
            records.store(second);
            records.store(big, [&](const char* table, std::size_t row) {
                if (std::string(table) == "errors" && row == 5000) {
                    const char go = 1;
                    if (::write(ready[1], &go, 1) != 1) ::_exit(3);
                    ::pause();  // killed here, mid-transaction
                }
            });
        } catch (...) {
            ::_exit(2);
        }
        ::_exit(4);  // the hook never ran
    }
    ::close(ready[1]);
    char go = 0;
    ASSERT_EQ(::read(ready[0], &go, 1), 1) << "the child failed before its third store";
    ::close(ready[0]);
    // the uncommitted exam is in the log, not just in the child's memory
    const auto wal = std::filesystem::path(file.string() + "-wal");
    EXPECT_GT(std::filesystem::file_size(wal), 4u << 20);
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

    const Records records(file, {.create = false});
    EXPECT_EQ(records.integrity_check(), "ok");
    const auto sessions = records.sessions();
    ASSERT_EQ(sessions.size(), 2u);
    EXPECT_EQ(sessions[0].case_id, "fv-isolated-acute");
    EXPECT_EQ(sessions[1].case_id, "healthy");
    EXPECT_EQ(records.stations(sessions[1].id).size(), 4u);
    EXPECT_EQ(records.errors(sessions[1].id).size(), 3u);
    EXPECT_TRUE(records.sessions("Killed Midway").empty());
    EXPECT_EQ(records.trainees(), std::vector<std::string>{"Ada Lovelace"});  // the half exam's trainee row went with it
    EXPECT_TRUE(records.errors(3).empty());
    std::filesystem::remove_all(file.parent_path());
}

TEST(Records, DefaultPathFollowsXdg)
{
    EXPECT_EQ(default_records_path("/data", "/home/a"), std::filesystem::path("/data/echosim/records.sqlite"));
    EXPECT_EQ(default_records_path("relative", "/home/a"), std::filesystem::path("/home/a/.local/share/echosim/records.sqlite"));
    EXPECT_EQ(default_records_path("", "/home/a"), std::filesystem::path("/home/a/.local/share/echosim/records.sqlite"));
    EXPECT_EQ(default_records_path(nullptr, "/home/a"), std::filesystem::path("/home/a/.local/share/echosim/records.sqlite"));
    EXPECT_THROW(default_records_path(nullptr, nullptr), RecordsError);
}

}  // namespace
}  // namespace echosim::exam

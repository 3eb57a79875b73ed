// `echosim records`: the trainee records (exam/records.hpp) listed with each trainee's learning
// curve (exam/learning_curve.hpp), `echosim records export --xapi F` (exam/xapi.hpp), and
// `echosim records add REPORT.json`, which stores an exam's report written elsewhere. Its own
// header, beside commands.hpp, so the command's options live with it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace echosim::app {

struct RecordsArgs {
    std::optional<std::string> trainee;  // --trainee NAME: only this trainee's sessions
    std::filesystem::path records;       // --records PATH; empty: the user's data folder's
    std::filesystem::path plot;          // --plot F.png: the learning curves; empty: none
    bool json = false;                   // --json: the listing as JSON on stdout
    std::filesystem::path xapi;          // export --xapi F.json
    std::string homepage = "https://echosim.org";  // export --homepage URL: the actors' accounts' home page (the lab's)
    std::filesystem::path report;        // add REPORT.json; --trainee then names whom it is stored under
};

// Exit codes as commands.hpp says: 0, 1 (the database could not be read), 2 (bad options).
int run_records(const RecordsArgs& args);
int run_records_export(const RecordsArgs& args);
int run_records_add(const RecordsArgs& args);

}  // namespace echosim::app

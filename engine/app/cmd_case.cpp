// `echosim case validate F [F...]` and `echosim case list`: an instructor's checks of the case
// files (exam/scenario.hpp) before a trainee meets them. Each file is read as the exam reads it, so
// a file that validates is one the exam runs.
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands.hpp"
#include "core/printable_text.hpp"
#include "exam/scenario.hpp"

namespace echosim::app {

int run_case(const CaseArgs& args)
{
    if (args.action == "list") {
        // every shipped case, read: a case that does not read is listed with its error, and fails the command
        int rc = kExitOk;
        for (const std::filesystem::path& file : exam::shipped_cases()) {
            try {
                const exam::Scenario sc = exam::read_scenario(file);
                std::printf("%-20s %s\n", sc.id.c_str(), printable(sc.title).c_str());
            } catch (const exam::ScenarioError& e) {
                std::fprintf(stderr, "echosim case list: %s\n", e.what());
                rc = kExitFailure;  // a shipped file is ours to fix, not the user's input
            }
        }
        return rc;
    }
    // validate: each file on its own line, all of them checked even after a bad one
    int rc = kExitOk;
    for (const std::filesystem::path& file : args.files) {
        try {
            const exam::Scenario sc = exam::read_scenario(file);
            std::printf("%s: ok (%s, %zu stations, %s)\n", printable(file.string()).c_str(), sc.id.c_str(), sc.stations.size(),
                        exam::protocol_name(sc.protocol));
        } catch (const exam::ScenarioError& e) {
            std::fprintf(stderr, "echosim case validate: %s\n", e.what());
            rc = kExitBadInput;
        }
    }
    std::fflush(stdout);
    return rc;
}

}  // namespace echosim::app

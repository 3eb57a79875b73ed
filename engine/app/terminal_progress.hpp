// A long task's progress on stderr, "<lead><stage> NN %", for the commands that make volumes (the
// default case's volume on first use, `echosim phantom`, `echosim reconstruct`). On a terminal, one
// line rewritten in place when the stage or the whole percent changes; in a log (a pipe, a file:
// CI's, a user's `2> log`), a line of its own at each stage's 0, 25, 50, 75 and 100 %, with no
// carriage returns or terminal codes to garble it. Copies (the std::function a task keeps) share
// one state; finish() ends the terminal's line, if any.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

namespace echosim::app {

class TerminalProgress {
public:
    explicit TerminalProgress(std::string lead);  // on stderr, a terminal when isatty says so
    TerminalProgress(std::string lead, std::FILE* out, bool terminal);
    void operator()(const std::string& stage, double done);  // done: 0..1
    void finish();  // after the last update: nothing when nothing was shown

private:
    struct State {
        std::string lead, stage;
        std::FILE* out = nullptr;
        int percent = -1;
        bool terminal = false, shown = false;
    };
    std::shared_ptr<State> state_;
};

}  // namespace echosim::app

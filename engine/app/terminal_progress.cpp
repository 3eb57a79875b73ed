#include "app/terminal_progress.hpp"

#include <algorithm>
#include <utility>

#include <unistd.h>

namespace echosim::app {

TerminalProgress::TerminalProgress(std::string lead) : TerminalProgress(std::move(lead), stderr, ::isatty(::fileno(stderr)) == 1) {}

TerminalProgress::TerminalProgress(std::string lead, std::FILE* out, bool terminal) : state_(std::make_shared<State>())
{
    state_->lead = std::move(lead);
    state_->out = out;
    state_->terminal = terminal;
}

void TerminalProgress::operator()(const std::string& stage, double done)
{
    State& s = *state_;
    const int whole = std::clamp(int(100 * done), 0, 100);
    const int percent = s.terminal ? whole : whole / 25 * 25;
    if (stage == s.stage && percent == s.percent) return;
    s.stage = stage;
    s.percent = percent;
    s.shown = true;
    // a terminal's line: back to its start, and clear what a longer one left; a log's: a line of its own
    std::fprintf(s.out, "%s%s%s %3d %%%s", s.terminal ? "\r" : "", s.lead.c_str(), stage.c_str(), percent, s.terminal ? "\033[K" : "\n");
    std::fflush(s.out);
}

void TerminalProgress::finish()
{
    if (state_->shown && state_->terminal) std::fputc('\n', state_->out);
    state_->shown = false;
}

}  // namespace echosim::app

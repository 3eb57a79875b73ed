#include "app/cyclictest.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace echosim::app {
namespace {

// its first line that is not a comment ('#': what it set up), without control characters, for a note
std::string first_line(std::string_view text)
{
    while (!text.empty()) {
        const std::size_t end = std::min(text.find('\n'), text.size());
        const std::string_view line = text.substr(0, end);
        text.remove_prefix(std::min(end + 1, text.size()));
        if (line.empty() || line.front() == '#') continue;
        std::string clean;
        for (char c : line)
            if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) clean += c;
        return clean.substr(0, 200);
    }
    return "";
}

}  // namespace

std::vector<double> parse_cyclictest_maxima_us(std::string_view output)
{
    std::vector<double> maxima;
    while (!output.empty()) {
        const std::size_t end = std::min(output.find('\n'), output.size());
        const std::string_view line = output.substr(0, end);
        output.remove_prefix(std::min(end + 1, output.size()));
        if (line.rfind("T:", 0) != 0) continue;
        const std::size_t at = line.find("Max:");
        if (at == std::string_view::npos) continue;
        const std::string number(line.substr(at + 4)), thread(line.substr(2, at - 2));
        char* stop = nullptr;
        const double v = std::strtod(number.c_str(), &stop);
        if (stop == number.c_str() || !std::isfinite(v) || v < 0) continue;
        char* thread_end = nullptr;
        const long n = std::strtol(thread.c_str(), &thread_end, 10);
        if (thread_end == thread.c_str() || n < 0 || n > 4096) continue;
        if (maxima.size() <= std::size_t(n)) maxima.resize(std::size_t(n) + 1, -1.0);
        maxima[std::size_t(n)] = v;
    }
    return maxima;
}

std::vector<int> allowed_cpus()
{
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return {};
    std::vector<int> cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) cpus.push_back(c);
    return cpus;
}

std::optional<double> CyclictestResult::max_on(int cpu) const
{
    for (const CyclictestCpu& c : cpus)
        if (c.cpu == cpu) return c.max_ms;
    return std::nullopt;
}

std::optional<double> parse_cyclictest_max_us(std::string_view output)
{
    std::optional<double> max;
    while (!output.empty()) {
        const std::size_t end = std::min(output.find('\n'), output.size());
        const std::string_view line = output.substr(0, end);
        output.remove_prefix(std::min(end + 1, output.size()));
        if (line.rfind("T:", 0) != 0) continue;
        const std::size_t at = line.find("Max:");
        if (at == std::string_view::npos) continue;
        const std::string number(line.substr(at + 4));
        char* stop = nullptr;
        const double v = std::strtod(number.c_str(), &stop);
        if (stop == number.c_str() || !std::isfinite(v) || v < 0) continue;
        max = std::max(max.value_or(v), v);
    }
    return max;
}

Cyclictest::Cyclictest(double seconds, const std::string& program, std::vector<int> cpus) : cpus_(std::move(cpus))
{
    const long duration = std::lround(std::ceil(std::max(seconds, 1.0))) + 1;
    std::vector<std::string> args = {program, "-m", "-p", std::to_string(kCyclictestPriority), "-i", std::to_string(kCyclictestIntervalUs),
                                     "-q", "-D", std::to_string(duration)};
    if (cpus_.empty()) cpus_ = allowed_cpus();
    if (!cpus_.empty()) {
        // a thread pinned on every CPU, all woken together (distance 0)
        std::string list;
        for (int c : cpus_) list += (list.empty() ? "" : ",") + std::to_string(c);
        args.insert(args.end(), {"-t", std::to_string(cpus_.size()), "-a", list, "-d", "0"});
    }
    for (const std::string& a : args) result_.command += (result_.command.empty() ? "" : " ") + a;
    int pipe_fds[2];
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) {
        result_.note = std::string("cyclictest not run: pipe: ") + std::strerror(errno);
        return;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int error = posix_spawnp(&pid_, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipe_fds[1]);
    if (error != 0) {
        ::close(pipe_fds[0]);
        pid_ = -1;
        result_.note = error == ENOENT ? "cyclictest is not installed (Debian package rt-tests; scripts/deps installs it)"
                                       : std::string("cyclictest not run: ") + std::strerror(error);
        return;
    }
    out_ = pipe_fds[0];
}

Cyclictest::~Cyclictest()
{
    if (pid_ > 0) finish();
}

CyclictestResult Cyclictest::finish(bool interrupt)
{
    if (pid_ <= 0) return result_;
    if (interrupt) ::kill(pid_, SIGINT);
    std::string output;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(out_, buffer, sizeof buffer);
        if (n > 0) {
            output.append(buffer, std::size_t(n));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        break;
    }
    ::close(out_);
    out_ = -1;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (const std::optional<double> us = parse_cyclictest_max_us(output)) {
        result_.max_ms = *us * 1e-3;
        const std::vector<double> maxima = parse_cyclictest_maxima_us(output);
        for (std::size_t n = 0; n < maxima.size() && n < cpus_.size(); ++n)
            if (maxima[n] >= 0) result_.cpus.push_back({cpus_[n], maxima[n] * 1e-3});
        return result_;
    }
    // no summary: it refused (most often the priority, without root or an rtprio limit) or failed
    std::string why = first_line(output);
    if (why.empty())
        why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                : "ended by signal " + std::to_string(WTERMSIG(status)) + " before its summary";
    result_.note = "cyclictest gave no figure: " + why;
    return result_;
}

}  // namespace echosim::app

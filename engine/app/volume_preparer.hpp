// The exam cases' volumes, made (or read from the cache) on a thread of their own while the window
// runs (issue 32 item 4): a case's volume takes half a minute to make the first time on the 2-core
// machine, and the window must not stand unpolled meanwhile (a kiosk's screen frozen, the desktop
// asking whether to kill it), nor open only once it is made.
//
//   - want(case): the case the trainee is about to need (the one the start screen chooses); the
//     worker makes or reads it first (a making under way for another case stops at its next
//     progress report, to be made again later if also_make asked for it) and holds it, ready to be
//     taken, until another is held;
//   - also_make(cases): after the wanted one, each case not yet cached is made and cached (the
//     kiosk's, so that its trainees never wait);
//   - pause(true) while a lesson runs: the making stops at its next progress report, so the exam's
//     physics and haptics have the machine's cores; the worker also runs at a lower priority
//     (nice 10: its GPU driver's threads, lavapipe's, inherit it);
//   - the destructor stops the making at its next progress report and waits for the worker.
// The worker's errors (a cache that cannot be written) are kept per case and shown, never thrown.
// Threads: any thread calls in; the state is under one mutex; the worker is the only thread that
// runs `load`.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/volume_source.hpp"
#include "exam/scenario.hpp"

namespace echosim::app {

class VolumePreparer {
public:
    using Progress = std::function<void(const std::string& stage, double done)>;
    // Makes or reads a case's volumes (exam_volume, cached); throws on failure.
    using Load = std::function<VolumePair(const exam::Scenario& c, const Progress& progress)>;
    // Whether a case's volumes are in the cache already (also_make skips those); one that throws
    // counts as not cached.
    using Cached = std::function<bool(const exam::Scenario& c)>;

    VolumePreparer(Load load, Cached cached, int nice = 10);
    ~VolumePreparer();
    VolumePreparer(const VolumePreparer&) = delete;
    VolumePreparer& operator=(const VolumePreparer&) = delete;

    void want(const exam::Scenario& c);
    void also_make(const std::vector<exam::Scenario>& cases);
    void pause(bool paused);

    enum class State { waiting, making, ready, failed };
    struct Status {
        State state = State::waiting;
        std::string stage;   // making: what it does now
        double done = 0;     // making: how far, 0..1
        std::string error;   // failed: why
    };
    Status status(const std::string& case_id) const;
    // The volumes of `case_id` when held (they stay held: a runner rebuilt takes them again).
    std::optional<VolumePair> take(const std::string& case_id) const;
    // Whether a volume is being made or read now.
    bool busy() const;
    // How many of also_make's cases are cached or held, of how many.
    std::pair<int, int> made() const;

private:
    struct Stopped {};    // thrown through `load` by the progress report when the preparer ends
    struct Preempted {};  // ... when another case is wanted first
    void work();
    bool wanted_needed() const;  // the wanted case is neither held nor failed (under the mutex)
    void report(const std::string& stage, double done);

    Load load_;
    Cached cached_;
    int nice_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<exam::Scenario> wanted_;
    std::deque<exam::Scenario> queue_;    // also_make's, not yet looked at
    int background_total_ = 0, background_done_ = 0;
    std::string held_id_;
    VolumePair held_;
    std::string current_id_;              // being made or read now
    std::string stage_;
    double done_ = 0;
    std::map<std::string, std::string> failed_;
    bool paused_ = false, stop_ = false;
    std::thread worker_;  // last: started once the rest is
};

}  // namespace echosim::app

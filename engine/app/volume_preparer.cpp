#include "app/volume_preparer.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <exception>

namespace echosim::app {

VolumePreparer::VolumePreparer(Load load, Cached cached, int nice)
    : load_(std::move(load)), cached_(std::move(cached)), nice_(nice), worker_([this] { work(); })
{
}

VolumePreparer::~VolumePreparer()
{
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

void VolumePreparer::want(const exam::Scenario& c)
{
    {
        std::lock_guard lock(mutex_);
        if (wanted_ && wanted_->id == c.id) return;
        wanted_ = c;
    }
    wake_.notify_all();
}

void VolumePreparer::also_make(const std::vector<exam::Scenario>& cases)
{
    {
        std::lock_guard lock(mutex_);
        for (const exam::Scenario& c : cases) queue_.push_back(c);
        background_total_ += int(cases.size());
    }
    wake_.notify_all();
}

void VolumePreparer::pause(bool paused)
{
    {
        std::lock_guard lock(mutex_);
        if (paused_ == paused) return;
        paused_ = paused;
    }
    wake_.notify_all();
}

VolumePreparer::Status VolumePreparer::status(const std::string& case_id) const
{
    std::lock_guard lock(mutex_);
    if (held_id_ == case_id) return {State::ready, "", 1.0, ""};
    if (const auto f = failed_.find(case_id); f != failed_.end()) return {State::failed, "", 0, f->second};
    if (current_id_ == case_id) return {State::making, stage_, done_, ""};
    return {};
}

std::optional<VolumePair> VolumePreparer::take(const std::string& case_id) const
{
    std::lock_guard lock(mutex_);
    if (held_id_ != case_id) return std::nullopt;
    return held_;
}

bool VolumePreparer::busy() const
{
    std::lock_guard lock(mutex_);
    return !current_id_.empty();
}

std::pair<int, int> VolumePreparer::made() const
{
    std::lock_guard lock(mutex_);
    return {background_done_, background_total_};
}

void VolumePreparer::report(const std::string& stage, double done)
{
    std::unique_lock lock(mutex_);
    stage_ = stage;
    done_ = done;
    // a lesson under way has the cores: the making waits here, mid-way, until it ends
    wake_.wait(lock, [&] { return stop_ || !paused_; });
    if (stop_) throw Stopped{};
    // another case is wanted now (the trainee chose it): it goes first; a background case is
    // made again later, a case no longer wanted only when wanted again
    if (wanted_needed() && wanted_->id != current_id_) throw Preempted{};
}

bool VolumePreparer::wanted_needed() const { return wanted_ && wanted_->id != held_id_ && !failed_.count(wanted_->id); }

void VolumePreparer::work()
{
    // the making yields to the window, the physics and the haptic loop (this thread alone on Linux;
    // the threads it starts, the GPU driver's among them, inherit it)
    if (nice_ > 0) setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), nice_);
    std::unique_lock lock(mutex_);
    for (;;) {
        // the next job: the wanted case unless held (or failed), else the next not yet cached
        std::optional<exam::Scenario> job;
        bool hold = false;
        wake_.wait(lock, [&] { return stop_ || (!paused_ && (wanted_needed() || !queue_.empty())); });
        if (stop_) return;
        if (wanted_needed()) {
            job = wanted_;
            hold = true;
        } else {
            job = queue_.front();
            queue_.pop_front();
            lock.unlock();
            bool cached = false;
            try {
                cached = cached_(*job);
            } catch (const std::exception&) {
                // (no cache folder: the making below says why, kept as the case's failure)
            }
            lock.lock();
            if (cached) {
                ++background_done_;
                continue;
            }
        }
        current_id_ = job->id;
        stage_ = "starting";
        done_ = 0;
        lock.unlock();
        VolumePair pair;
        std::optional<std::string> error;
        try {
            pair = load_(*job, [this](const std::string& stage, double done) { report(stage, done); });
        } catch (const Stopped&) {
            return;
        } catch (const Preempted&) {
            lock.lock();
            current_id_.clear();
            if (!hold) queue_.push_front(*job);
            continue;
        } catch (const std::exception& e) {
            error = e.what();
        } catch (...) {
            error = "an unknown error";
        }
        if (!error && !pair.volume) error = "no volume was made";
        lock.lock();
        current_id_.clear();
        if (error) {
            failed_[job->id] = *error;
        } else if (hold) {
            held_id_ = job->id;
            held_ = std::move(pair);
        } else {
            ++background_done_;
        }
    }
}

}  // namespace echosim::app
